// `swell foam` for wave cases: a piston paddle becomes an interFoam waveModels inlet (StokesI,
// StokesII, the solitary model Boussinesq), a damping zone an absorbing outlet; what cannot be
// mapped is refused. The last test runs a short coarse flume in interFoam (skipped, with a
// message, where OpenFOAM is not installed) and checks the wave height at the first gauge.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "case/reader.hpp"
#include "foam/foam.hpp"
#include "foam/plan.hpp"
#include "waves/dispersion.hpp"

namespace fs = std::filesystem;
using namespace swell;

namespace {

const std::string kCase = std::string(SWELL_SOURCE_DIR) + "/tests/data/foam_waves_small.yaml";
constexpr double kPi = std::numbers::pi;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The case file's text with its motion line (and, if asked, its damping zone) replaced.
CaseSpec wave_case(const std::string& motion, bool damping = true) {
  std::string text = read(kCase);
  const auto m = text.find("    motion:");
  text.replace(m, text.find('\n', m) - m, "    motion: " + motion);
  if (!damping) {
    const auto d = text.find("damping:");
    text.erase(d, text.find("gauges:") - d);
  }
  return parse_case_text(text, kCase);
}

fs::path write(const CaseSpec& spec, const std::string& name) {
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_foam_waves" / name;
  fs::remove_all(d);
  FoamOptions o;
  o.out_dir = d.string();
  o.cell_size = 0.01;
  std::ostringstream log;
  write_foam_case(spec, o, log);
  return d;
}

// The number after `key` (up to ';') in a dictionary text; NaN if absent.
double entry(const std::string& text, const std::string& key) {
  const auto k = text.find("    " + key + " ");
  if (k == std::string::npos) return std::nan("");
  return std::stod(text.substr(k + key.size() + 5, text.find(';', k) - k - key.size() - 5));
}

std::string word(const std::string& text, const std::string& key) {
  const auto k = text.find("    " + key + " ");
  if (k == std::string::npos) return "";
  std::istringstream in(text.substr(k + key.size() + 5));
  std::string w;
  in >> w;
  return w.substr(0, w.find(';'));
}

std::string refusal(const CaseSpec& spec) {
  try {
    write(spec, "refused");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(FoamWaves, RegularPaddleBecomesAStokesInletAndDampingAnOutlet) {
  const CaseSpec spec = wave_case(
      "{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, order: 2, "
      "phase: 30, ramp: 1.5}");
  const fs::path d = write(spec, "regular");
  const std::string wp = read(d / "constant/waveProperties");
  const std::string inlet = wp.substr(wp.find("inlet\n{"), wp.find("}") - wp.find("inlet\n{"));
  EXPECT_EQ(word(inlet, "waveModel"), "StokesII");
  EXPECT_DOUBLE_EQ(entry(inlet, "waveHeight"), 0.04);
  EXPECT_DOUBLE_EQ(entry(inlet, "wavePeriod"), 1.0);
  EXPECT_DOUBLE_EQ(entry(inlet, "waterDepthRef"), 0.3);
  EXPECT_DOUBLE_EQ(entry(inlet, "rampTime"), 1.5);
  EXPECT_DOUBLE_EQ(entry(inlet, "waveAngle"), 0.0);
  // eta_SPH(x, t) = a cos(w t + phi - k x), x from the paddle face at x0 = 0.13 m; the inlet
  // imposes a cos(k x0 - w t + P): P = -(phi + k x0) mod 2 pi. k for T = 1 s in 0.3 m from
  // w^2 = g k tanh(k d): L = 1.37295 m (Newton's method in python, independently).
  const double k = waves::wave_number(2 * kPi, 0.3, 9.81);
  EXPECT_NEAR(2 * kPi / k, 1.37295, 1e-5);
  const double phase = std::fmod(-(kPi / 6 + k * 0.13) + 4 * kPi, 2 * kPi);
  EXPECT_NEAR(entry(inlet, "wavePhase"), phase, 1e-9);
  EXPECT_NE(wp.find("waveModel       shallowWaterAbsorption"), std::string::npos);

  // The mesh starts at the paddle face; 2D: the case's vertical y is OpenFOAM's z.
  const std::string bm = read(d / "system/blockMeshDict");
  EXPECT_NE(bm.find("(0.13 -0.005 0)"), std::string::npos) << bm;
  EXPECT_NE(bm.find("(3 0.005 0.45)"), std::string::npos) << bm;
  EXPECT_NE(bm.find("(287 1 45)"), std::string::npos) << bm;  // (3 - 0.13) / 0.01 = 287
  EXPECT_NE(bm.find("inlet\n    {\n        type patch;\n        faces\n        (\n"
                    "            (0 4 7 3)"),
            std::string::npos);
  EXPECT_NE(bm.find("outlet\n    {\n        type patch;\n        faces\n        (\n"
                    "            (2 6 5 1)"),
            std::string::npos);
  EXPECT_NE(bm.find("frontAndBack\n    {\n        type empty;\n        faces\n        (\n"
                    "            (1 5 4 0)\n            (3 7 6 2)"),
            std::string::npos);
  EXPECT_NE(read(d / "constant/g").find("(0 0 -9.81)"), std::string::npos);
  const std::string u = read(d / "0.orig/U"), a = read(d / "0.orig/alpha.water");
  EXPECT_NE(u.find("inlet\n    {\n        type waveVelocity;"), std::string::npos);
  EXPECT_NE(u.find("outlet\n    {\n        type waveVelocity;"), std::string::npos);
  EXPECT_NE(a.find("inlet\n    {\n        type waveAlpha;"), std::string::npos);
  // Water below 0.3 m (OpenFOAM z), the gauge line vertical at x = 1.13 m.
  EXPECT_NE(read(d / "system/setFieldsDict").find("1 0.29999999)"), std::string::npos);
  // (1e-4 cell off the cell face at x = 1.13 m)
  EXPECT_NE(read(d / "system/controlDict").find("(1.130001 0 0.0025)"), std::string::npos);

  // A water box that starts a particle gap off the paddle (as SPH cases do) reaches the inlet.
  std::string text = read(kCase);
  const auto f = text.find("    fill:");
  text.replace(f, text.find('\n', f) - f, "    shape: {box: {min: [0.145, 0], max: [3.0, 0.3]}}");
  const fs::path db = write(parse_case_text(text, kCase), "box");
  EXPECT_NE(read(db / "system/setFieldsDict").find("box (0.13 -1 1e-08)"), std::string::npos)
      << read(db / "system/setFieldsDict");

  // First order, no damping zone: StokesI, and the far end stays a wall.
  const fs::path d1 =
      write(wave_case("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0}", false),
            "regular1");
  const std::string wp1 = read(d1 / "constant/waveProperties");
  EXPECT_EQ(word(wp1, "waveModel"), "StokesI");
  EXPECT_DOUBLE_EQ(entry(wp1, "rampTime"), 2.0);  // the SPH default: two periods
  EXPECT_EQ(wp1.find("outlet"), std::string::npos);
  const std::string bm1 = read(d1 / "system/blockMeshDict");
  EXPECT_EQ(bm1.find("outlet"), std::string::npos);
  EXPECT_NE(bm1.find("tank\n    {\n        type wall;\n        faces\n        (\n"
                     "            (2 6 5 1)\n            (0 3 2 1)"),
            std::string::npos)
      << bm1;
}

TEST(FoamWaves, SolitaryPaddleBecomesTheBoussinesqModelWithItsCrestInTime) {
  const CaseSpec spec =
      wave_case("{type: wave, wave: solitary, depth: 0.3, height: 0.06, start: 0.5}");
  const fs::path d = write(spec, "solitary");
  const std::string wp = read(d / "constant/waveProperties");
  EXPECT_EQ(word(wp, "waveModel"), "Boussinesq");
  EXPECT_DOUBLE_EQ(entry(wp, "waveHeight"), 0.06);
  EXPECT_TRUE(std::isnan(entry(wp, "rampTime")));
  // Goring's crest passes the paddle's rest face at t = start + (3.8 + H/d) / (kappa c) -
  // (S/2) / c (S = 2 H / (kappa d), the trajectory's start ~ -S/2 to 1e-3 S); interFoam's at
  // its inlet at 3.5 d sqrt(d/H) / c. OpenFOAM t = 0 is the difference.
  const double H = 0.06, h = 0.3, c = std::sqrt(9.81 * (h + H));
  const double kappa = std::sqrt(3 * H / (4 * h * h * h)), S = 2 * H / (kappa * h);
  const double offset =
      0.5 + (3.8 + H / h) / (kappa * c) - 0.5 * S / c - 3.5 * h * std::sqrt(h / H) / c;
  const foam::Plan plan = foam::make_plan(spec, FoamOptions{"", 0.01});
  EXPECT_NEAR(plan.time_offset, offset, 2e-3 * S / c);
  EXPECT_NEAR(plan.end_time, 5.0 - plan.time_offset, 1e-12);
  EXPECT_NE(read(d / "constant/waveProperties").find("case time"), std::string::npos);
}

TEST(FoamWaves, WhatCannotBeMappedIsRefusedNamingTheBodyAndKey) {
  const std::string flap = refusal(
      wave_case("{type: wave, paddle: flap, hinge: [0.115, 0.05], wave: regular, depth: 0.3, "
                "height: 0.04, period: 1.0}"));
  EXPECT_NE(flap.find("body paddle, motion: paddle: flap"), std::string::npos) << flap;
  const std::string irregular = refusal(
      wave_case("{type: wave, wave: irregular, depth: 0.3, hs: 0.03, tp: 1.2, components: 20}"));
  EXPECT_NE(irregular.find("wave: irregular cannot be mapped"), std::string::npos) << irregular;
  const std::string focused =
      refusal(wave_case("{type: wave, wave: focused, depth: 0.3, amplitude: 0.03, tp: 1.2, "
                        "focus_distance: 2.0, focus_time: 8.0}"));
  EXPECT_NE(focused.find("wave: focused cannot be mapped"), std::string::npos) << focused;
  const std::string sine =
      refusal(wave_case("{type: sinusoidal, amplitude: 0.01, period: 1.0, direction: [1, 0]}"));
  EXPECT_NE(sine.find("body paddle, motion: swell foam cannot map a prescribed motion"),
            std::string::npos)
      << sine;
  const std::string back = refusal(wave_case(
      "{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, direction: [-1, 0]}"));
  EXPECT_NE(back.find("motion: direction"), std::string::npos) << back;
  const std::string stop = refusal(
      wave_case("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, stop: 3.0}"));
  EXPECT_NE(stop.find("motion: stop"), std::string::npos) << stop;
}

// interFoam runs the coarse flume (3.5 s, 12.5 mm cells): the first gauge (1 m from the
// paddle) must read the wave height H = 0.04 m within 15 % over the last period (the waves
// reach it at ~1.5 s, after the 1 s ramp).
TEST(FoamWaves, InterFoamMakesTheWaveHeightAtTheFirstGauge) {
  std::string why;
  if (!openfoam_available(&why))
    GTEST_SKIP() << "OpenFOAM (interFoam) not installed: " << why
                 << " -- the interFoam wave run did not run";
  const CaseSpec spec = load_case_file(kCase);
  FoamOptions o;
  o.out_dir = (fs::path(SWELL_BINARY_DIR) / "test_foam_waves" / "e2e").string();
  fs::remove_all(o.out_dir);
  o.run = true;
  o.cell_size = 0.0125;  // 3.2 cells per wave height
  o.end_time = 3.5;
  std::ostringstream log;
  FoamResult r;
  try {
    r = run_foam_case(spec, o, log);
  } catch (const FoamError& e) {
    FAIL() << e.what() << "\n" << log.str();
  }
  std::ifstream in(fs::path(r.gauge_dir) / "gauges_height.csv");
  ASSERT_TRUE(in) << r.gauge_dir;
  std::string line;
  double lo = 1e9, hi = -1e9, mean = 0.0;
  int rows = 0;
  bool header = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      header = true;
      EXPECT_EQ(line.rfind("time", 0), 0u) << line;  // the SPH format: time [s],WG1 [m]
      EXPECT_NE(line.find(",WG1"), std::string::npos) << line;
      continue;
    }
    const double t = std::stod(line.substr(0, line.find(',')));
    const double v = std::stod(line.substr(line.find(',') + 1));
    if (t < 2.5 - 1e-9) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    mean += v;
    ++rows;
  }
  EXPECT_GE(rows, 45);  // every 0.02 s over [2.5, 3.5] s
  std::cout << "interFoam: " << r.cells << " cells, " << r.steps << " steps, " << r.wall_seconds
            << " s; WG1 over t = 2.5-3.5 s: crest " << hi << " m, trough " << lo << " m, H "
            << hi - lo << " m (target 0.04 m)\n";
  EXPECT_NEAR(hi - lo, 0.04, 0.15 * 0.04);
  // The mean level stays the still-water depth (to the surface reading's cell/8 bias).
  mean /= std::max(rows, 1);
  std::cout << "mean level " << mean << " m\n";
  EXPECT_NEAR(mean, 0.3, 0.004);
}

// 2D wave cases are written with OpenFOAM's z up: what interFoam writes (points, U, forces and
// moments in its axes, times from the wave's start) comes back in case axes and case time.
TEST(FoamWaves, GaugesOfAZUpCaseComeBackInCaseAxesAndTime) {
  CaseSpec spec =
      wave_case("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, start: 0.5}");
  GaugeSpec v;
  v.name = "V1";
  v.kind = GaugeSpec::Kind::Velocity;
  v.at = Eigen::Vector3d(1.0, 0.2, 0);
  spec.gauges.push_back(v);
  GaugeSpec force;
  force.name = "F_tank";
  force.kind = GaugeSpec::Kind::Force;
  force.body = "tank";
  spec.gauges.push_back(force);
  const fs::path dir = write(spec, "convert");
  FoamOptions opt;
  opt.out_dir = dir.string();
  opt.cell_size = 0.01;
  const foam::Plan plan = foam::make_plan(spec, opt);
  ASSERT_TRUE(plan.z_up);
  EXPECT_DOUBLE_EQ(plan.time_offset, 0.5);
  EXPECT_DOUBLE_EQ(plan.end_time, 4.5);

  const fs::path pp = dir / "postProcessing";
  const foam::Probe& hp = plan.probes[0];
  ASSERT_EQ(hp.spec.name, "WG1");
  fs::create_directories(pp / hp.function / "0.2");
  std::ofstream h(pp / hp.function / "0.2" / "WG1_alpha.water.xy");
  for (int k = 0; k < hp.points; ++k) {  // OpenFOAM (x, y, z): wet below z = 0.31
    const double z = hp.start.y() + k * (hp.end.y() - hp.start.y()) / (hp.points - 1);
    h << "1.130001\t0\t" << z << "\t" << (z < 0.31 ? 1.0 : 0.0) << "\n";
  }
  h.close();
  fs::create_directories(pp / plan.probes[1].function / "0");
  std::ofstream(pp / plan.probes[1].function / "0/U")
      << "# Probe 0 (1 0 0.2)\n#   Probe 0\n#   Time\n   0.2   (0.5 0 -0.25)\n";
  fs::create_directories(pp / "force_F_tank/0");
  std::ofstream(pp / "force_F_tank/0/force.dat")
      << "# Force\n# Time\t(total_x total_y total_z)\n0.2\t(0.01 0 -0.02)\t(0 0 0)\t(0 0 0)\n";
  std::ofstream(pp / "force_F_tank/0/moment.dat")
      << "# Moment\n0.2\t(0 0.004 0)\t(0 0 0)\t(0 0 0)\n";
  std::ostringstream log;
  const auto files = convert_foam_gauges(spec, opt, (dir / "gauges").string(), log);
  EXPECT_EQ(files.size(), 3u);
  const std::string hcsv = read(dir / "gauges/gauges_height.csv");
  const auto row = hcsv.find("\n0.7,");  // OpenFOAM t = 0.2 is case time 0.7
  ASSERT_NE(row, std::string::npos) << hcsv;
  EXPECT_NEAR(std::stod(hcsv.substr(row + 5)), 0.31, 0.003);  // within one sample (cell/4)
  EXPECT_NE(read(dir / "gauges/gauges_velocity.csv").find("\n0.7,0.5,-0.25\n"), std::string::npos)
      << read(dir / "gauges/gauges_velocity.csv");
  // Per metre of width (one 10 mm cell); the case's moment about z is -M_y of OpenFOAM (the
  // y <-> z swap is a reflection).
  EXPECT_NE(read(dir / "gauges/gauges_force.csv").find("\n0.7,1,-2,-0.4\n"), std::string::npos)
      << read(dir / "gauges/gauges_force.csv");
}

// An absorbing piston (absorption:) is mapped to the same inlet, with a note saying that the
// inlet's own active absorption replaces the paddle's (gain, filter and drift are not mapped);
// a paddle without absorption gets no such note.
TEST(FoamWaves, AbsorbingPistonIsMappedWithANote) {
  auto notes = [](const CaseSpec& spec) {
    FoamOptions o;
    o.cell_size = 0.01;
    std::string all;
    for (const auto& n : foam::make_plan(spec, o).notes) all += n + "\n";
    return all;
  };
  const std::string with = notes(wave_case(
      "{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, absorption: true}"));
  EXPECT_NE(with.find("active absorption (absorption:) is not mapped as such"), std::string::npos)
      << with;
  EXPECT_NE(with.find("inlet (StokesI)"), std::string::npos) << with;
  const std::string without =
      notes(wave_case("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0}"));
  EXPECT_EQ(without.find("absorption"), std::string::npos) << without;
}
