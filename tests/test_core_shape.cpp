// The shape of the core (ARCHITECTURE.md): one field table that every per-particle
// operation iterates, step hooks carrying moving bodies through restarts bit for bit, and the
// dependency rules between folders.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "bc/moving_bodies.hpp"
#include "case/reader.hpp"
#include "io/hdf5_file.hpp"
#include "run/run.hpp"
#include "tests/case_run.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("swell_test_core_" + name);
  fs::remove_all(d);
  return d;
}

// A field added to the table follows its particle through the cell sort and a checkpoint: the
// optional reference position pos_ref, given a value that identifies the particle.
TEST(FieldTable, AFieldFollowsItsParticleThroughSortAndCheckpoint) {
  ParticleSet<2> ps;
  for (int i = 0; i < 300; ++i) {
    // Reverse-ordered positions, so the sort really permutes.
    const double x = 0.001 * (299 - i) + 0.0005, y = 0.01 * (i % 7) + 0.005;
    ps.add(Vec<2>(x, y), Vec<2>(i, -i), 1000.0 + i, 0.1, i % 5 ? Role::Fluid : Role::MovingWall,
           static_cast<std::uint16_t>(i % 3));
  }
  std::vector<Vec<2>> tag(ps.total());
  for (std::size_t i = 0; i < tag.size(); ++i) tag[i] = Vec<2>(7.0 * i, -3.0 * i);
  ps.enable("pos_ref", tag);
  // The mDBC normals (and their body-frame copy, and the moving walls' accelerations) are
  // optional fields of the same kind.
  std::vector<Vec<2>> ntag(ps.total()), nref(ps.total()), acc(ps.total());
  for (std::size_t i = 0; i < tag.size(); ++i) {
    ntag[i] = Vec<2>(0.5 * i, 2.0);
    nref[i] = Vec<2>(-1.0, 0.25 * i);
    acc[i] = Vec<2>(3.0 * i, 0.125);
  }
  ps.enable("normal", ntag);
  ps.enable("normal_ref", nref);
  ps.enable("wall_acc", acc);
  int enabled = 0;
  ps.for_each_field([&](const FieldInfo& f, const auto&) { enabled += ps.enabled(f); });
  EXPECT_EQ(enabled, ParticleSet<2>::kNumFields);

  CellGrid<2> grid(Vec<2>(0, 0), Vec<2>(0.31, 0.08), 0.004);
  grid.sort(ps);
  ASSERT_EQ(ps.size(), 300u);
  int moved = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const std::uint32_t id = ps.id[i];
    moved += id != i;
    EXPECT_EQ(ps.pos_ref[i], Vec<2>(7.0 * id, -3.0 * id)) << "pos_ref of particle " << id;
    EXPECT_EQ(ps.normal[i], Vec<2>(0.5 * id, 2.0)) << "normal of particle " << id;
    EXPECT_EQ(ps.normal_ref[i], Vec<2>(-1.0, 0.25 * id)) << "normal_ref of particle " << id;
    EXPECT_EQ(ps.wall_acc[i], Vec<2>(3.0 * id, 0.125)) << "wall_acc of particle " << id;
    EXPECT_EQ(ps.rho[i], 1000.0 + id);
    EXPECT_EQ(ps.velocity(i), Vec<2>(id, -double(id)));
  }
  EXPECT_GT(moved, 250) << "the sort did not reorder";

  const fs::path d = fresh_dir("fields");
  fs::create_directories(d);
  const std::string ck = (d / "checkpoint.h5").string();
  write_checkpoint<2>(ck, ps, SimulationClock{}, {{"x", 1.0}});
  const Checkpoint<2> c = read_checkpoint<2>(ck);
  EXPECT_EQ(c.particles.pos_ref, ps.pos_ref);
  EXPECT_EQ(c.particles.normal, ps.normal);
  EXPECT_EQ(c.particles.normal_ref, ps.normal_ref);
  EXPECT_EQ(c.particles.wall_acc, ps.wall_acc);
  EXPECT_EQ(c.particles.role, ps.role);
  EXPECT_EQ(c.particles.id, ps.id);
  c.particles.for_each_field([&](const FieldInfo& f, const auto& a) {
    EXPECT_TRUE(c.particles.enabled(f)) << f.name;
    EXPECT_EQ(a.size(), ps.total()) << f.name;
  });

  // Without moving bodies the optional field stays off: not allocated, not written.
  ParticleSet<2> plain;
  plain.add(Vec<2>(0.1, 0.1), Vec<2>::Zero(), 1000.0, 0.1, Role::Fluid, 0);
  EXPECT_TRUE(plain.pos_ref.empty());
  EXPECT_TRUE(plain.normal.empty());
  write_checkpoint<2>(ck, plain, SimulationClock{}, {});
  EXPECT_TRUE(read_checkpoint<2>(ck).particles.pos_ref.empty());
  EXPECT_TRUE(read_checkpoint<2>(ck).particles.normal.empty());
}

// A flap hinged at the bed, rocking +-15 degrees: after one period every particle is back at
// its start to round-off, and half-way it has turned rigidly about the hinge.
TEST(MovingBodies, FlapReturnsToItsStartPoseAfterOnePeriod) {
  MotionSpec m;
  m.type = MotionSpec::Type::Rotation;
  m.centre = Eigen::Vector3d(0.5, 0.0, 0.0);
  m.amplitude = 15.0 * M_PI / 180.0;
  m.period = 1.7;
  m.phase = 0.3;
  const std::vector<MotionLaw> laws{MotionLaw(), MotionLaw(m)};
  ParticleSet<2> ps;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 3; ++i)
      ps.add(Vec<2>(0.49 + 0.01 * i, 0.005 + 0.01 * j), Vec<2>::Zero(), 1000.0, 0.1,
             Role::FixedWall, 1);
  ps.add(Vec<2>(0.2, 0.2), Vec<2>::Zero(), 1000.0, 0.1, Role::Fluid, 0);
  MovingBodies<2>::prepare(ps, laws);
  EXPECT_EQ(ps.role[0], Role::MovingWall);
  EXPECT_EQ(ps.role.back(), Role::Fluid);
  const std::vector<Vec<2>> start = ps.pos;
  MovingBodies<2> hook(laws);
  CellGrid<2> grid;
  ForceBuffers<2> f;
  SolverParams prm;
  const TaitEos eos(1000.0, 10.0, 7.0);
  for (double t : {0.4, 0.5 * 1.7, 1.7, 2.0 * 1.7}) {
    StepState<2> s{ps, grid, f, prm, eos, t, 0.0};
    hook.prescribe(s);
    const bool full = std::abs(std::remainder(t, 1.7)) < 1e-12;
    double worst = 0.0, rigid = 0.0;
    for (std::size_t i = 0; i + 1 < ps.size(); ++i) {
      worst = std::max(worst, (ps.pos[i] - start[i]).norm());
      const Vec<2> c(0.5, 0.0);
      rigid = std::max(rigid, std::abs((ps.pos[i] - c).norm() - (start[i] - c).norm()));
    }
    if (full)
      EXPECT_LT(worst, 1e-12) << "t = " << t;
    else
      EXPECT_GT(worst, 1e-3) << "t = " << t << ": the flap did not move";
    EXPECT_LT(rigid, 1e-12) << "t = " << t;
    EXPECT_EQ(ps.pos.back(), Vec<2>(0.2, 0.2)) << "fluid is not prescribed";
  }
}

// A piston paddle driving waves into a short flume.
std::string paddle_case(double t_end, double amplitude = 0.01) {
  std::ostringstream s;
  s << "name: paddle\ndim: 2\ndp: 0.005\ntime: {end: " << t_end << "}\n"
    << "bodies:\n"
    << "  - {name: flume, kind: boundary, shape: {box: {min: [0, 0], max: [0.6, 0.2]}}, "
       "layers: 3, open: [ymax]}\n"
    << "  - {name: paddle, kind: boundary, shape: {box: {min: [0.04, 0.0], max: [0.055, 0.16]}}, "
       "walls: outside, layers: 3, motion: {type: sinusoidal, amplitude: "
    << amplitude << ", period: 0.5, direction: [1, 0], ramp: 0.1}}\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0.07, 0], max: [0.6, 0.1]}}}\n"
    << "gauges:\n  - {name: Fpaddle, kind: force, body: paddle}\n"
    << "  - {name: H1, kind: height, at: [0.3, 0.0]}\n"
    << "output: {every: 0.02, vtk: false, hdf5: true, gauge_every: 0.005}\n";
  return s.str();
}

RunSummary run(const std::string& text, const fs::path& dir, bool restart, int threads,
               bool overwrite = false) {
  return test::run_case_text(text, "paddle.yaml", dir, restart, threads, overwrite);
}

using test::read_text;

TEST(MovingBodies, RestartWithMotionIsBitwise) {
  const fs::path a = fresh_dir("full"), b = fresh_dir("split");
  run(paddle_case(0.12), a, false, 2);
  run(paddle_case(0.06), b, false, 1);  // stops half-way, inside the ramp ...
  run(paddle_case(0.12), b, true, 2);   // ... and continues with another thread count
  const auto ca = read_checkpoint<2>((a / "checkpoint.h5").string());
  const auto cb = read_checkpoint<2>((b / "checkpoint.h5").string());
  ASSERT_EQ(ca.clock.steps, cb.clock.steps);
  EXPECT_GT(ca.clock.steps, 300);
  EXPECT_EQ(ca.particles.id, cb.particles.id);
  EXPECT_EQ(ca.particles.pos, cb.particles.pos);
  EXPECT_EQ(ca.particles.vel, cb.particles.vel);
  EXPECT_EQ(ca.particles.rho, cb.particles.rho);
  EXPECT_EQ(ca.particles.pos_ref, cb.particles.pos_ref);
  EXPECT_EQ(ca.schedule, cb.schedule);
  // The paddle did move and pushed on the water.
  double moved = 0.0;
  for (std::size_t i = 0; i < ca.particles.size(); ++i)
    if (ca.particles.role[i] == Role::MovingWall)
      moved = std::max(moved, (ca.particles.pos[i] - ca.particles.pos_ref[i]).norm());
  EXPECT_GT(moved, 0.002);
  for (const char* f : {"gauges_force.csv", "gauges_height.csv", "diagnostics.csv"})
    EXPECT_EQ(read_text(a / f), read_text(b / f)) << f;
  EXPECT_EQ(run(paddle_case(0.12), a, false, 1, true).excluded.total(), 0u);
}

TEST(MovingBodies, RestartRefusesAChangedMotion) {
  const fs::path d = fresh_dir("changed");
  run(paddle_case(0.03), d, false, 2);
  try {
    run(paddle_case(0.06, 0.02), d, true, 2);
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("motion was changed"), std::string::npos) << e.what();
  }
}

// The floors (ARCHITECTURE.md): each folder includes only its own floor and the floors below
// it. solver/ includes nothing outside solver/ (Eigen, OpenMP and the standard library only);
// waves/ is pure maths; bc/ sees the solver and the wave maths; geometry/ the solver; case/ the
// numerics and geometry; io/ (the data back end) the case's types; run/ everything below it;
// foam/, validation/, verify/ and bench/ stand beside run/ and include neither it nor each
// other; apps/ alone stands above them all ("swell/" is the build's generated version and
// commit headers).
TEST(Layout, EachFloorIncludesOnlyTheFloorsBelowIt) {
  const fs::path src(SWELL_SOURCE_DIR);
  const std::regex inc("#include\\s+\"([^\"]+)\"");
  auto check = [&](const std::string& folder, const std::vector<std::string>& allowed) {
    int files = 0;
    for (const auto& e : fs::recursive_directory_iterator(src / folder)) {
      if (!e.is_regular_file()) continue;
      const auto ext = e.path().extension();
      if (ext != ".hpp" && ext != ".cpp") continue;
      ++files;
      std::ifstream f(e.path());
      std::string line;
      while (std::getline(f, line)) {
        std::smatch m;
        if (!std::regex_search(line, m, inc)) continue;
        const std::string target = m[1];
        bool ok = false;
        for (const auto& a : allowed) ok = ok || target.rfind(a, 0) == 0;
        EXPECT_TRUE(ok) << e.path() << " includes \"" << target << "\"";
      }
    }
    EXPECT_GT(files, 3) << folder;
  };
  check("solver", {"solver/"});
  check("waves", {"waves/"});
  check("bc", {"solver/", "bc/", "waves/"});
  check("geometry", {"solver/", "geometry/"});
  check("parallel", {"solver/", "parallel/"});
  check("case", {"solver/", "waves/", "bc/", "geometry/", "case/"});
  check("io", {"solver/", "case/", "io/", "swell/"});
  check("run",
        {"solver/", "waves/", "bc/", "geometry/", "case/", "io/", "parallel/", "run/", "swell/"});
  check("foam", {"solver/", "waves/", "geometry/", "case/", "io/", "foam/"});
  check("validation", {"solver/", "waves/", "geometry/", "case/", "io/", "validation/"});
  check("verify", {"solver/", "waves/", "bc/", "geometry/", "case/", "io/", "verify/"});
  check("bench", {"solver/", "waves/", "bc/", "geometry/", "case/", "io/", "bench/"});
  // The intrinsics live in one file of the solver.
  for (const auto& e : fs::recursive_directory_iterator(src / "solver")) {
    if (!e.is_regular_file()) continue;
    std::ifstream f(e.path());
    std::stringstream s;
    s << f.rdbuf();
    const bool intrinsics = s.str().find("_mm512_") != std::string::npos;
    EXPECT_EQ(intrinsics, e.path().filename() == "gather.hpp") << e.path();
  }
}

}  // namespace
}  // namespace swell
