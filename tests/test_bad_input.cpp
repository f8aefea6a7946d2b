// Bad input and blow-ups (issue #15, part B): every input in tests/data/bad/ through the real
// `swell run` command, asserting the exit code (2 bad input, 3 unstable) and the message, and
// that none of them crashes, hangs or eats the machine (each run has a time limit). Then the
// watchdog and the exclusion bookkeeping on hand-made particle sets.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bc/dbc.hpp"
#include "case/reader.hpp"
#include "case/setup.hpp"
#include "io/hdf5_file.hpp"
#include "solver/diagnostics.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string output;
};

const std::string kBad = std::string(SWELL_SOURCE_DIR) + "/tests/data/bad/";

fs::path out_dir(const std::string& name) {
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_bad_input" / name;
  fs::remove_all(d);
  fs::create_directories(d.parent_path());
  return d;
}

// `swell run CASE -o OUT -t 1 -q` under a time limit (exit 124 when it runs over).
Result run_swell(const std::string& case_file, const fs::path& out, int limit_s = 60) {
  const std::string cmd = "timeout " + std::to_string(limit_s) + " " + SWELL_BINARY_DIR +
                          "/swell run " + case_file + " -o " + out.string() + " -t 1 -q 2>&1";
  Result r;
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) r.output += buf;
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

void expect_contains(const std::string& text, const std::vector<std::string>& parts) {
  for (const auto& part : parts) EXPECT_NE(text.find(part), std::string::npos) << part;
}

struct BadCase {
  const char* file;
  int code;
  std::vector<std::string> message;
};

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, ExitCodeAndMessage) {
  const BadCase& c = GetParam();
  const std::string stem = fs::path(c.file).stem().string();
  const fs::path out = out_dir(stem);
  const Result r = run_swell(kBad + c.file, out);
  std::cout << "  " << c.file << " -> exit " << r.code << ": " << r.output.substr(0, 300) << "\n";
  EXPECT_EQ(r.code, c.code) << r.output;
  expect_contains(r.output, c.message);
  EXPECT_EQ(r.output.find("Segmentation"), std::string::npos);
  // A run refused before it wrote anything leaves no folder behind (-o named a new one).
  if (c.code == 2) EXPECT_FALSE(fs::exists(out)) << out;
}

INSTANTIATE_TEST_SUITE_P(
    Issue15, BadInput,
    ::testing::Values(
        // 7: a one-byte case file (yaml-cpp 0.7 LoadAll allocated without bound)
        BadCase{"comma.yaml", 2, {"comma.yaml:1:", "expected a map"}},
        // 6: particle counts and memory, refused before the fill
        BadCase{"dp_tiny_3d.yaml",
                2,
                {"dp_tiny_3d.yaml", "would make up to", "particles", "available", "dp^-3"}},
        BadCase{"dp_tiny_2d.yaml", 2, {"would make up to", "'water'", "available"}},
        BadCase{"layers_huge.yaml", 2, {"would make up to", "'tank' 4e+10", "wall"}},
        BadCase{"max_particles.yaml", 2, {"limits.max_particles is 100"}},
        // 8: malformed meshes with repair: true
        BadCase{"mesh_nan.yaml", 2, {"mesh_nan.stl", "vertex 2", "non-finite"}},
        BadCase{"mesh_inf.yaml", 2, {"mesh_inf.stl", "vertex 1", "non-finite"}},
        BadCase{"mesh_1e30.yaml", 2, {"mesh_1e30.stl", "vertex 1", "1e+30", "+-1e+06 m"}},
        BadCase{"mesh_7e22.yaml", 2, {"mesh_7e22.stl", "6.8e+22", "+-1e+06 m"}},
        // found by fuzz_mesh_stl: SIGSEGV in CGAL's autorefinement
        BadCase{"mesh_denormal.yaml", 2, {"mesh_denormal.stl", "spans only", "at least 1e-6 m"}},
        // 8: a mesh CGAL's autorefinement gives up on (it threw "Non-handled triple
        // intersection"; under the fuzzers' clang build the exception ended in std::terminate;
        // with CGAL's assertions on, as in scripts/sanitize, an assertion fails first: either
        // is a mesh error)
        BadCase{"mesh_triple.yaml",
                2,
                {"mesh_triple.stl", "70 pairs of faces intersect", "gave up", "fix the mesh"}},
        BadCase{"mesh_sliver.yaml",
                2,
                {"mesh_sliver.stl", "pairs of faces intersect", "under 1e-07 of its size"}},
        // 10: geometry near 1e30 m (UBSan: float to long overflow in the fill)
        BadCase{"far_geometry.yaml", 2, {"body 'water' reaches x = 1e+30 m", "+-1e+06 m"}},
        // 5: a start outside the density bounds is a setup error
        BadCase{
            "coefsound1.yaml",
            2,
            {"initial hydrostatic density", "physics.density_bounds", "coefsound = 1", "particle"}},
        // 12: setup errors detectable before step 1
        BadCase{"fluid_outside_domain.yaml",
                2,
                {"fluid_outside_domain.yaml:8:", "fluid body 'drop'", "outside the domain"}},
        BadCase{"domain_cuts_walls.yaml", 2, {"boundary body 'tank'", "cuts its walls"}},
        BadCase{"gauge_outside.yaml",
                2,
                {"gauge_outside.yaml:10:", "gauges[0] 'P9'", "outside the domain"}},
        BadCase{"gravity_zero.yaml", 2, {"gravity_zero.yaml:4:", "physics.gravity", "non-zero"}},
        BadCase{"coefh_absurd.yaml", 2, {"coefh_absurd.yaml:4:", "physics.coefh", "[0.5, 4]"}},
        // damping zones and settling (bc/damping.hpp): a zero direction, a zero rate
        BadCase{"damping_zero_direction.yaml",
                2,
                {"damping_zero_direction.yaml:9:", "damping[0].plane.direction", "non-zero"}},
        BadCase{"settling_rate_zero.yaml",
                2,
                {"settling_rate_zero.yaml:4:", "time.settling.rate", "a number > 0"}},
        BadCase{"warnings.yaml",
                0,
                {"warning: body 'water' (line 8): fill level 0.5 m lies above the top of 'tank'",
                 "warning: gauges[0] 'P_in_block' (line 10)", "inside the solid 'block'"}}),
    [](const ::testing::TestParamInfo<BadCase>& info) {
      std::string name = fs::path(info.param.file).stem().string();
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

// 5: a dam break whose speed of sound is far too low loses its water through the density
// bounds; the watchdog stops it with exit 3, and the checkpoint left is one of a healthy state.
TEST(Watchdog, BlowUpStopsWithExit3AndKeepsTheLastHealthyCheckpoint) {
  const fs::path out = out_dir("blowup_density");
  const Result r = run_swell(kBad + "blowup_density.yaml", out);
  std::cout << r.output;
  EXPECT_EQ(r.code, 3);
  expect_contains(r.output, {"error: the run went unstable", "of the fluid mass has been excluded",
                             "watchdog.max_excluded = 5 %", "density out of range",
                             "Likely cause: the pressure field blew up",
                             "was taken while the run was healthy"});
  ASSERT_TRUE(fs::exists(out / "checkpoint.h5"));
  const Checkpoint<2> ck = read_checkpoint<2>((out / "checkpoint.h5").string());
  std::size_t fluid_total = 0, fluid_active = 0;
  for (std::size_t i = 0; i < ck.particles.total(); ++i) {
    if (ck.particles.role[i] != Role::Fluid) continue;
    ++fluid_total;
    fluid_active += i < ck.particles.size();
  }
  const double lost = 1.0 - static_cast<double>(fluid_active) / static_cast<double>(fluid_total);
  std::cout << "  checkpoint at t = " << ck.clock.time << " s: " << 100 * lost << " % excluded\n";
  EXPECT_GT(ck.clock.time, 0.0);
  EXPECT_LE(lost, 0.05);
}

// 4, 5: water pouring out of an open side: stopped (exit 3) naming the face, or, with the
// limit raised, reported by face and time in the summary with the 0.1 % warning.
TEST(Watchdog, WaterLeavingThroughASideIsNamedByFace) {
  const Result r = run_swell(kBad + "side_leak.yaml", out_dir("side_leak"));
  EXPECT_EQ(r.code, 3) << r.output;
  expect_contains(r.output, {"out through x+", "Last through x+: particle",
                             "Likely cause: water is leaving through a side of the domain"});
}

TEST(Exclusions, ReportedByFaceAndTimeWithAWarning) {
  const fs::path out = out_dir("side_leak_allowed");
  fs::create_directories(out.parent_path());
  const std::string case_file = (out.parent_path() / "side_leak_allowed.yaml").string();
  {
    std::ifstream in(kBad + "side_leak.yaml");
    std::ofstream o(case_file);
    o << in.rdbuf() << "watchdog: {max_excluded: 1.0}\n";
  }
  const Result r = run_swell(case_file, out);
  std::cout << r.output;
  EXPECT_EQ(r.code, 0) << r.output;
  expect_contains(r.output, {"warning: ", "% of the fluid mass has been excluded by t = ",
                             "over watchdog.warn_excluded = 0.1 %",
                             "    through x+: ", "(warning: over watchdog.warn_excluded = 0.1 %)"});
  EXPECT_EQ(r.output.find("through x-"), std::string::npos);
  EXPECT_EQ(r.output.find("through y"), std::string::npos);
}

// The default domain: the particles' box + 10 % + 2h on each side, and 50 % of its height more
// above the water (against gravity); printed in the run header.
TEST(Domain, DefaultRuleAndHeader) {
  const CaseSpec spec = load_case_file(std::string(SWELL_SOURCE_DIR) + "/cases/dambreak2d.yaml");
  const CaseSetup<2> s = setup_case<2>(spec);
  Vec<2> lo = s.particles.pos[0], hi = lo;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    lo = lo.cwiseMin(s.particles.pos[i]);
    hi = hi.cwiseMax(s.particles.pos[i]);
  }
  const Vec<2> margin = (0.1 * (hi - lo)).array() + 2.0 * s.params.h;
  EXPECT_DOUBLE_EQ(s.params.domain_min.x(), lo.x() - margin.x());
  EXPECT_DOUBLE_EQ(s.params.domain_max.x(), hi.x() + margin.x());
  EXPECT_DOUBLE_EQ(s.params.domain_min.y(), lo.y() - margin.y());
  EXPECT_DOUBLE_EQ(s.params.domain_max.y(), hi.y() + margin.y() + 0.5 * (hi.y() - lo.y()));
  EXPECT_TRUE(s.default_domain);
  const Result r = run_swell(kBad + "warnings.yaml", out_dir("header"));
  expect_contains(r.output, {"  domain: [", "] x [", "(default: the particles' box + 10 % + 2h"});
}

// Hand-made sets for the watchdog's other checks: a wall floor at y = -dp/2, fluid above it.
struct Rig {
  SolverParams prm;
  ParticleSet<2> ps;
  Rig() {
    prm.dp = 0.01;
    prm.h = 1.4 * prm.dp;
    prm.c0 = 10.0;
    prm.domain_min = Eigen::Vector3d(-1, -1, 0);
    prm.domain_max = Eigen::Vector3d(1, 1, 0);
    const double m = prm.rho0 * prm.dp * prm.dp;
    for (int i = 0; i < 20; ++i)
      ps.add(Vec<2>((i + 0.5) * prm.dp, -0.5 * prm.dp), Vec<2>::Zero(), prm.rho0, m,
             Role::FixedWall, 0);
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j)
        ps.add(Vec<2>((i + 5.5) * prm.dp, (j + 0.5) * prm.dp), Vec<2>::Zero(), prm.rho0, m,
               Role::Fluid, 1);
  }
};

std::string check_message(Watchdog<2>& w, const Simulation<2>& sim) {
  try {
    w.check(sim);
  } catch (const InstabilityError& e) {
    return e.what();
  }
  return "";
}

TEST(Watchdog, HealthyStateRaisesNothing) {
  Rig rig;
  Simulation<2> sim(rig.prm, rig.ps, make_dbc<2>());
  Watchdog<2> w(WatchdogLimits{}, sim, 0.0);
  EXPECT_FALSE(w.check(sim));
  EXPECT_EQ(w.excluded_fraction(), 0.0);
}

TEST(Watchdog, FluidBelowTheFloorIsPenetration) {
  Rig rig;
  for (int i = 0; i < 3; ++i) rig.ps.pos[20 + i].y() = -0.12;  // 12 cm under the floor
  Simulation<2> sim(rig.prm, rig.ps, make_dbc<2>());
  Watchdog<2> w(WatchdogLimits{}, sim, 0.0);
  const std::string m = check_message(w, sim);
  std::cout << m << "\n";
  expect_contains(m, {"3 fluid particles are more than 2 dp below the lowest wall particle",
                      "watchdog.max_penetrated", "Likely cause: water went through the DBC floor",
                      "the deepest, particle 2"});
  // Beside the walls (outside their horizontal extent) it is a fall, not a leak.
  Rig beside;
  for (int i = 0; i < 3; ++i) beside.ps.pos[20 + i] = Vec<2>(0.5, -0.12);
  Simulation<2> sim2(beside.prm, beside.ps, make_dbc<2>());
  Watchdog<2> w2(WatchdogLimits{}, sim2, 0.0);
  EXPECT_EQ(check_message(w2, sim2), "");
}

TEST(Watchdog, WallDensityFarFromRho0Stops) {
  Rig rig;
  rig.ps.rho[3] = 2.5 * rig.prm.rho0;
  Simulation<2> sim(rig.prm, rig.ps, make_dbc<2>());
  Watchdog<2> w(WatchdogLimits{}, sim, 0.0);
  const std::string m = check_message(w, sim);
  expect_contains(m, {"wall particle 3", "density 2.5 rho0", "watchdog.max_density = 2 rho0"});
  // With the case's body names the message names the body, not its index.
  const std::size_t body = rig.ps.body[3];
  std::vector<std::string> names(body + 1, "other");
  names[body] = "tank";
  w.set_body_names(names);
  expect_contains(check_message(w, sim), {"wall particle 3 (body 'tank')"});
  WatchdogLimits loose;
  loose.max_density_factor = 3.0;
  Watchdog<2> w3(loose, sim, 0.0);
  EXPECT_EQ(check_message(w3, sim), "");
}

TEST(Watchdog, ExclusionsAreFiledByFace) {
  Rig rig;
  rig.ps.pos[20] = Vec<2>(1.5, 0.1);    // x+
  rig.ps.pos[21] = Vec<2>(0.1, 1.2);    // y+
  rig.ps.pos[22] = Vec<2>(0.1, 1.3);    // y+
  rig.ps.pos[23] = Vec<2>(-1.1, -1.5);  // farther below than left: y-
  rig.ps.pos[3] = Vec<2>(-2.0, 0.0);    // a wall particle, x-
  Simulation<2> sim(rig.prm, rig.ps, make_dbc<2>());
  const FaceExclusions& f = sim.excluded_faces();
  EXPECT_EQ(f.particles, (std::array<std::size_t, 6>{1, 1, 1, 2, 0, 0}));
  EXPECT_EQ(f.fluid, (std::array<std::size_t, 6>{0, 1, 1, 2, 0, 0}));
  EXPECT_DOUBLE_EQ(f.fluid_mass[3], 2 * rig.ps.mass[21]);
  EXPECT_EQ(f.first_time[3], 0.0);
  EXPECT_EQ(f.first_time[4], -1.0);
  EXPECT_EQ(f.last_id[3], 22u);
  EXPECT_EQ(sim.excluded().out_of_domain, 5u);
  // 4 of 100 fluid particles: over the 0.1 % warning, under the 5 % stop.
  Watchdog<2> w(WatchdogLimits{}, sim, 0.0);
  EXPECT_TRUE(w.check(sim));
  EXPECT_NEAR(w.excluded_fraction(), 0.04, 1e-12);
  expect_contains(w.warning(), {"4 % of the fluid mass", "2 fluid (2 in all) out through y+"});
  EXPECT_FALSE(w.check(sim));  // the warning is given once
  WatchdogLimits tight;
  tight.max_excluded_fraction = 0.03;
  Watchdog<2> w2(tight, sim, 0.0);
  expect_contains(check_message(w2, sim), {"4 % of the fluid mass", "watchdog.max_excluded = 3 %",
                                           "Last through y+: particle 22"});
}

}  // namespace
}  // namespace swell
