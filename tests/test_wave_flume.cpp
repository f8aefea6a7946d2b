// Wavemakers end to end: the `motion: {type: wave}` case keys, the paddle's motion law (piston
// and flap) and a short, coarse regular-wave flume whose first gauge must read the target wave
// height and period.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "apps/wave_target_command.hpp"
#include "bc/absorption.hpp"
#include "case/reader.hpp"
#include "case_run.hpp"
#include "validation/metrics.hpp"
#include "waves/theory.hpp"
#include "waves/wavemaker.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

std::string flume_case(const std::string& motion, double end = 1.0) {
  std::ostringstream c;
  c << "dim: 2\ndp: 0.015\ntime: {end: " << end << "}\nbodies:\n"
    << "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [3.5, 0.5]}}, layers: 3,"
       " open: [ymax]}\n"
    << "  - name: paddle\n    kind: boundary\n"
       "    shape: {box: {min: [0.1, 0.0], max: [0.13, 0.45]}}\n    walls: outside\n"
       "    layers: 2\n"
    << "    motion: " << motion << "\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0.145, 0], max: [3.5, 0.3]}}}\n";
  return c.str();
}

TEST(WaveCaseKeys, RegularPistonAndFlap) {
  const CaseSpec s = parse_case_text(
      flume_case("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, order: 2}"),
      "flume.yaml");
  const MotionSpec& m = s.bodies[1].motion;
  ASSERT_EQ(m.type, MotionSpec::Type::Wave);
  ASSERT_TRUE(m.paddle);
  const waves::PaddleSignal ref = waves::regular_paddle(
      {waves::PaddleGeometry::Type::Piston, 0.3, 0.0}, 0.04, 1.0, 2, 0.0, 9.81);
  ASSERT_EQ(m.paddle->components.size(), 2u);
  EXPECT_DOUBLE_EQ(m.paddle->components[0].amplitude, ref.components[0].amplitude);
  EXPECT_DOUBLE_EQ(m.paddle->components[1].amplitude, ref.components[1].amplitude);
  EXPECT_DOUBLE_EQ(m.ramp, 2.0);  // default: two periods
  EXPECT_NE(m.wave_label.find("order 2"), std::string::npos);

  const CaseSpec f = parse_case_text(
      flume_case("{type: wave, paddle: flap, wave: regular, depth: 0.3, height: 0.03, "
                 "period: 1.2, hinge: [0.115, 0.05], ramp: 1.0}"),
      "flume.yaml");
  const MotionSpec& fm = f.bodies[1].motion;
  EXPECT_DOUBLE_EQ(fm.lever, 0.25);
  EXPECT_DOUBLE_EQ(fm.ramp, 1.0);
  EXPECT_EQ(fm.paddle->paddle.type, waves::PaddleGeometry::Type::Flap);
  EXPECT_DOUBLE_EQ(fm.paddle->paddle.hinge_height, 0.05);
  // Where the flap crosses the still-water level (`lever` above the hinge) it is displaced by
  // exactly X(t): the line from the hinge through a point of the plate, cut at the SWL.
  const MotionLaw law(fm);
  const Eigen::Vector3d hinge(0.115, 0.05, 0.0), swl(0.115, 0.3, 0.0);
  for (double t : {1.3, 1.7, 2.9}) {  // after the 1 s ramp
    Eigen::Vector3d x, v;
    law.place(law.pose(t), swl, x, v);
    const Eigen::Vector3d u = x - hinge;
    EXPECT_NEAR(u.x() * 0.25 / u.y(), fm.paddle->displacement(t), 1e-13) << t;
    EXPECT_GT(std::abs(fm.paddle->displacement(t)), 1e-3) << t;
    const double e = 1e-6;
    Eigen::Vector3d xp, xm, dummy;
    law.place(law.pose(t + e), swl, xp, dummy);
    law.place(law.pose(t - e), swl, xm, dummy);
    EXPECT_NEAR(v.x(), (xp.x() - xm.x()) / (2 * e), 1e-7) << t;
    EXPECT_EQ(x.z(), 0.0);
  }

  // Irregular and focused seas, solitary waves.
  const CaseSpec irr = parse_case_text(
      flume_case("{type: wave, wave: irregular, depth: 0.3, hs: 0.03, tp: 1.2, gamma: 3.3, "
                 "components: 50, seed: 7}"),
      "flume.yaml");
  EXPECT_EQ(irr.bodies[1].motion.paddle->components.size(), 50u);
  EXPECT_EQ(irr.bodies[1].motion.paddle->pair_components, 0u);  // first order by default
  // order: 2 adds the bound long wave's pair terms; a flap refuses it.
  const CaseSpec irr2 = parse_case_text(
      flume_case("{type: wave, wave: irregular, depth: 0.3, hs: 0.03, tp: 1.2, gamma: 3.3, "
                 "components: 50, seed: 7, order: 2}"),
      "flume.yaml");
  EXPECT_EQ(irr2.bodies[1].motion.paddle->pair_components, 50u);
  EXPECT_EQ(irr2.bodies[1].motion.paddle->pair_paddle.size(), 50u * 49u / 2u);
  EXPECT_NE(irr2.bodies[1].motion.wave_label.find("bound long wave, 1225 pairs"), std::string::npos)
      << irr2.bodies[1].motion.wave_label;
  EXPECT_TRUE(irr2.bodies[1].motion.wave_notes.empty());
  // From 500 components at order 2 the pair count's cost is noted (the run header prints it).
  for (const int n : {499, 500}) {
    const CaseSpec many = parse_case_text(
        flume_case("{type: wave, wave: irregular, depth: 0.3, hs: 0.03, tp: 1.2, components: " +
                   std::to_string(n) + ", order: 2}"),
        "flume.yaml");
    const auto& notes = many.bodies[1].motion.wave_notes;
    if (n < 500) {
      EXPECT_TRUE(notes.empty()) << n;
      continue;
    }
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("124750 pair terms"), std::string::npos) << notes[0];
  }
  try {
    parse_case_text(flume_case("{type: wave, paddle: flap, hinge: [0.115, 0.05], wave: "
                               "irregular, depth: 0.3, hs: 0.03, tp: 1.2, order: 2}"),
                    "flume.yaml");
    ADD_FAILURE() << "a second-order flap sea was accepted";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("pistons only"), std::string::npos) << e.what();
  }
  const CaseSpec foc = parse_case_text(
      flume_case("{type: wave, wave: focused, depth: 0.3, amplitude: 0.03, tp: 1.2, "
                 "focus_distance: 2.0, focus_time: 8.0}"),
      "flume.yaml");
  EXPECT_EQ(foc.bodies[1].motion.paddle->components.size(), 60u);
  const CaseSpec sol = parse_case_text(
      flume_case("{type: wave, wave: solitary, depth: 0.3, height: 0.06}"), "flume.yaml");
  EXPECT_TRUE(sol.bodies[1].motion.paddle->solitary);
  EXPECT_DOUBLE_EQ(sol.bodies[1].motion.ramp, 0.0);
  EXPECT_FALSE(sol.bodies[1].motion.absorption);
}

// `swell waves target`: the case's target wave at distances from the paddle, ramped as the
// paddle is, and its bound part (the second-order signal's elevation less the linear one's).
TEST(WaveTarget, CaseTargetAndBoundPart) {
  const fs::path dir = fs::temp_directory_path() / "swell_wave_target_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string motion =
      "{type: wave, wave: irregular, depth: 0.3, hs: 0.04, tp: 1.2, components: 2, f_min: "
      "0.6, f_max: 1.0, order: 2, ramp: 2.0, start: 0.5}";
  { std::ofstream(dir / "c.yaml") << flume_case(motion, 10.0); }
  WavesTargetOptions opt;
  opt.case_file = (dir / "c.yaml").string();
  opt.at = "0.5,2";
  opt.end = 6.0;
  opt.every = 0.25;
  std::ostringstream out;
  run_waves_target(opt, out);
  const CaseSpec spec = parse_case_text(flume_case(motion, 10.0), "c.yaml");
  const waves::PaddleSignal& full = *spec.bodies[1].motion.paddle;
  waves::PaddleSignal lin = full;
  lin.pair_components = 0;
  std::istringstream in(out.str());
  std::string line;
  int rows = 0;
  double largest_bound = 0.0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::vector<double> v;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 5u) << line;
    const double t = v[0], tau = t - 0.5;
    double ramp = tau <= 0.0 ? 0.0 : 1.0;
    if (tau > 0.0 && tau < 2.0) ramp = (tau / 2) * (tau / 2) * (3 - tau);
    for (int k = 0; k < 2; ++k) {
      const double x = k == 0 ? 0.5 : 2.0;
      const double e = ramp * full.elevation(tau, x), b = e - ramp * lin.elevation(tau, x);
      EXPECT_NEAR(v[1 + 2 * k], e, 1e-8) << t;
      EXPECT_NEAR(v[2 + 2 * k], b, 1e-8) << t;
      largest_bound = std::max(largest_bound, std::abs(v[2 + 2 * k]));
    }
    ++rows;
  }
  EXPECT_EQ(rows, 25);
  EXPECT_GT(largest_bound, 1e-4);  // the pair's set-down is there
  // At the paddle's rest face (--at 0), and never past --end: 2.5 intervals give t = 0, 0.4, 0.8.
  opt.at = "0";
  opt.end = 1.0;
  opt.every = 0.4;
  std::ostringstream at0;
  run_waves_target(opt, at0);
  std::vector<double> times;
  std::istringstream in0(at0.str());
  while (std::getline(in0, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    times.push_back(std::stod(line));
    const double e = std::stod(line.substr(line.find(',') + 1)), tau = times.back() - 0.5;
    const double s = std::clamp(tau / 2.0, 0.0, 1.0);
    EXPECT_NEAR(e, tau > 0.0 ? s * s * (3 - 2 * s) * full.elevation(tau, 0.0) : 0.0, 1e-8);
  }
  EXPECT_EQ(times, (std::vector<double>{0.0, 0.4, 0.8}));
  // An end a whole number of intervals away, not exact in binary (0.3 / 0.1 = 2.9999...96):
  // its last row is kept.
  opt.end = 0.3;
  opt.every = 0.1;
  std::ostringstream tenths;
  run_waves_target(opt, tenths);
  int n_rows = 0;
  std::istringstream in1(tenths.str());
  while (std::getline(in1, line))
    if (!line.empty() && line[0] != '#' && line[0] != 't') ++n_rows;
  EXPECT_EQ(n_rows, 4);
  opt.at = "-1";
  EXPECT_THROW(run_waves_target(opt, out), std::invalid_argument);
  opt.at = "0.5,2";
  opt.end = 6.0;
  opt.every = 0.25;
  // A CSV into a folder that does not exist is refused before anything is computed.
  opt.csv = (dir / "missing" / "t.csv").string();
  EXPECT_THROW(run_waves_target(opt, out), std::invalid_argument);
  opt.csv.clear();
  // A case without a wavemaker is refused, naming the file.
  {
    std::ofstream(dir / "still.yaml") << "dim: 2\ndp: 0.02\ntime: {end: 1}\nbodies:\n"
                                         "  - {name: w, kind: fluid, shape: {box: {min: [0, 0], "
                                         "max: [1, 0.2]}}}\n";
  }
  opt.case_file = (dir / "still.yaml").string();
  try {
    run_waves_target(opt, out);
    ADD_FAILURE() << "a case without a wave was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("still.yaml"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// Active absorption: the keys, the defaults and the gains (bc/absorption.hpp).
TEST(WaveCaseKeys, Absorption) {
  const CaseSpec reg = parse_case_text(
      flume_case("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, bed: 0.0, "
                 "absorption: true}"),
      "flume.yaml");
  const MotionSpec& m = reg.bodies[1].motion;
  ASSERT_TRUE(m.absorption);
  EXPECT_EQ(m.absorption->gain, MotionSpec::Absorption::Gain::Tuned);
  const PaddleAbsorber a(m);
  // Tuned: w / F(kd) at T = 1 s, d = 0.3 m; the defaults 0.02 T and 10 T.
  const double w = 2 * kPi, k = waves::wave_number(w, 0.3, 9.81);
  const double kd = k * 0.3, f = 2 * (std::cosh(2 * kd) - 1) / (std::sinh(2 * kd) + 2 * kd);
  EXPECT_NEAR(a.gain(), w / f, 1e-12);
  EXPECT_NEAR(a.filter_time(), 0.02, 1e-12);
  EXPECT_NEAR(a.drift_time(), 10.0, 1e-12);
  const CaseSpec sol =
      parse_case_text(flume_case("{type: wave, wave: solitary, depth: 0.3, height: 0.06, "
                                 "absorption: {distance: 0.05, filter: 0, drift: 30}}"),
                      "flume.yaml");
  const MotionSpec& ms = sol.bodies[1].motion;
  ASSERT_TRUE(ms.absorption);
  EXPECT_EQ(ms.absorption->gain, MotionSpec::Absorption::Gain::Shallow);
  EXPECT_DOUBLE_EQ(*ms.absorption->distance, 0.05);
  const PaddleAbsorber as(ms);
  EXPECT_NEAR(as.gain(), std::sqrt(9.81 / 0.3), 1e-12);
  EXPECT_EQ(as.filter_time(), 0.0);
  EXPECT_EQ(as.drift_time(), 30.0);
  const CaseSpec off = parse_case_text(
      flume_case("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, "
                 "absorption: false}"),
      "flume.yaml");
  EXPECT_FALSE(off.bodies[1].motion.absorption);
}

// Each bad key is reported at its line, naming the key and what was expected.
TEST(WaveCaseKeys, BadKeysAreReported) {
  const auto message = [](const std::string& motion) -> std::string {
    try {
      parse_case_text(flume_case(motion), "flume.yaml");
    } catch (const CaseError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, hs: 0.1}")
                .find("a regular wave takes no 'hs' (it belongs to wave: irregular)"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, order: 2, "
                    "paddle: flap, hinge: [0.1, 0]}")
                .find("pistons only"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, "
                    "hinge: [0.1, 0]}")
                .find("'hinge' is for a flap"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: solitary, depth: 0.3, height: 0.04, ramp: 1}")
                .find("takes no ramp"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, period: 1}").find("height"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: -0.3, height: 0.04, period: 1}")
                .find("bodies[1].motion.depth"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, "
                    "paddle: flap, hinge: [0.1, 0.4]}")
                .find("below the still-water level"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: cnoidal, depth: 0.3}").find("regular"), std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, "
                    "paddle: flap, hinge: [0.1, 0], absorption: true}")
                .find("pistons only"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: solitary, depth: 0.3, height: 0.04, "
                    "absorption: {gain: tuned}}")
                .find("no period to tune to"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, "
                    "absorption: {filter: -1}}")
                .find("bodies[1].motion.absorption.filter: expected a time >= 0 s"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, "
                    "absorption: {gian: tuned}}")
                .find("absorption.gian: unknown key"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, "
                    "absorption: 3}")
                .find("absorption"),
            std::string::npos);
  EXPECT_NE(message("{type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1, "
                    "direction: [1, 1]}")
                .find("horizontally"),
            std::string::npos);
}

// Least-squares fit of a0 + sum_n (A_n cos n w t + B_n sin n w t), n = 1, 2, over [t0, t1];
// returns the first and second harmonic amplitudes.
std::pair<double, double> harmonics(const Series& s, double w, double t0, double t1) {
  Eigen::MatrixXd a(0, 5);
  std::vector<double> rows_t, rows_v;
  for (std::size_t i = 0; i < s.t.size(); ++i)
    if (s.t[i] >= t0 && s.t[i] <= t1) rows_t.push_back(s.t[i]), rows_v.push_back(s.v[i]);
  a.resize(static_cast<Eigen::Index>(rows_t.size()), 5);
  Eigen::VectorXd b(static_cast<Eigen::Index>(rows_t.size()));
  for (std::size_t i = 0; i < rows_t.size(); ++i) {
    const double t = rows_t[i];
    a.row(static_cast<Eigen::Index>(i)) << 1.0, std::cos(w * t), std::sin(w * t),
        std::cos(2 * w * t), std::sin(2 * w * t);
    b[static_cast<Eigen::Index>(i)] = rows_v[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  return {std::hypot(c[1], c[2]), std::hypot(c[3], c[4])};
}

// The frequency (scanned over +-10 % of w0 in steps of 0.05 %) whose least-squares harmonic fit
// has the largest first-harmonic amplitude over [t0, t1]: the wave's period, robust to the
// surface noise that makes single zero crossings scatter by a few percent at coarse dp.
double fitted_period(const Series& s, double w0, double t0, double t1) {
  double best = 0.0, best_w = w0;
  for (double f = 0.9; f <= 1.1; f += 0.0005) {
    const double a = harmonics(s, f * w0, t0, t1).first;
    if (a > best) best = a, best_w = f * w0;
  }
  return 2 * kPi / best_w;
}

// A 2D piston flume, depth 0.3 m, H = 0.04 m, T = 1 s (kd = 1.37, a2/a1 = 0.075: second-order
// generation), dp = 0.015 m (H/dp = 2.7: coarse), coefsound 10 (half the steps of the default
// 20; the flow's Mach number stays below 0.02), the wave settings of
// docs/user-guide/waves.md#settings-for-wave-runs (coefh 1.5, 4 wall layers, water's laminar
// viscosity), mDBC walls, ramp 1 s, a damping zone over the last 1.3 m (1 L) so that the window
// can be five periods of the steady wave, 3-8 s. The first gauge stands 0.45 m (1.5 d, 0.33 L) from
// the paddle, past its evanescent modes (the first, k1 = 9.08 rad/m from w^2 = -g k1 tan k1 d,
// decays to 1.7 % there); a second one at 0.9 m (0.66 L).
//
// Measured here (first-harmonic height 2 a1 at 0.45 / 0.9 m, 1 thread each):
//   mDBC dp 0.015 (this test)  -1.1 / -5.2 %      DBC dp 0.015  -4.0 / -6.9 %
//   mDBC dp 0.01               -2.3 / -4.5 %      DBC dp 0.01   -4.8 / -5.7 %
// DBC is 4-5 % low by the first gauge whatever the dp here: the gap between the plate and the fluid
// breathes under the paddle's pressure by a fraction of dp, which is half the stroke (0.031 m)
// at dp 0.015 (docs/validation/wave_decay.md: -2.4 % at 0.25 L with H/dp 5, stroke 7 dp). The
// further loss to 0.66 L is numerical decay of a wave this coarse (2-3 % per wavelength at H/dp
// 5-10 with these settings). So the issue's test target, H within 5 %, is asserted at the first
// gauge; the second gets 10 %, which catches a return to coefh 1 with artificial viscosity 0.01
// (21 % low there) and the paddle's own errors (a transfer function off by a factor, stroke
// taken for amplitude, a flap formula for a piston: factors 0.5-2). The period is the issue's
// target, 1 %, at both gauges (measured 0.9930 / 1.0055 s; with DBC 0.9965 / 1.0045 s: the
// scan's estimate over five periods scatters by about 0.7 % around the paddle's period).
TEST(WaveFlume, RegularWaveHeightAndPeriodAtTheFirstGauge) {
  const double H = 0.04, T = 1.0;
  std::string text = R"(dim: 2
dp: 0.015
physics: {coefsound: 10, coefh: 1.5, viscosity: {model: laminar, nu: 1.0e-6}, boundary: {model: mdbc}}
time: {end: 8.0}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [2.8, 0.5]}}, layers: 4,
     open: [ymax]}
  - name: paddle
    kind: boundary
    shape: {box: {min: [0.07, 0.0], max: [0.13, 0.45]}}
    walls: outside
    layers: 4
    motion: {type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, order: 2,
             ramp: 1.0}
  - {name: water, kind: fluid, shape: {box: {min: [0.145, 0], max: [2.8, 0.3]}}}
damping:
  - {name: beach, plane: {at: [1.5, 0], direction: [1, 0]}, length: 1.3}
gauges:
  - {name: eta1, kind: height, at: [0.45, 0.0], sampling: mean}
  - {name: eta2, kind: height, at: [0.9, 0.0], sampling: mean}
output: {every: 1.0, vtk: false, gauge_every: 0.01}
)";
  const fs::path dir = fs::path(SWELL_BINARY_DIR) / "test_out" / "wave_flume_regular";
  fs::remove_all(dir);
  test::run_case_text(text, "wave_flume.yaml", dir, false, 2);
  const SeriesTable table = read_series_table((dir / "gauges_height.csv").string());
  const Series eta1 = table.series("eta1"), eta2 = table.series("eta2");
  const auto [a1, a2] = harmonics(eta1, 2 * kPi / T, 3.0, 8.0);
  const double far = harmonics(eta2, 2 * kPi / T, 3.0, 8.0).first;
  const double period = fitted_period(eta1, 2 * kPi / T, 3.0, 8.0);
  const double period_far = fitted_period(eta2, 2 * kPi / T, 3.0, 8.0);
  std::cout << "first harmonic H = " << 2 * a1 << " m at 0.45 m, " << 2 * far
            << " m at 0.9 m (target " << H << "), a2/a1 = " << a2 / a1 << " (Stokes "
            << waves::stokes2_harmonic_ratio(waves::wave_number(2 * kPi / T, 0.3), 0.3, H)
            << "), T = " << period << " / " << period_far << " s\n";
  EXPECT_NEAR(2 * a1 / H, 1.0, 0.05);
  EXPECT_GT(2 * far / H, 0.9);
  EXPECT_LT(2 * far / H, 1.05);
  EXPECT_NEAR(period, T, 0.01 * T);
  EXPECT_NEAR(period_far, T, 0.01 * T);
}

// A `sampling: mean` height gauge writes the interval mean of the level: compared with the mean
// of a finely sampled instant gauge at the same place, in a swaying tank whose surface moves.
// Active absorption (bc/absorption.hpp) on a solitary wave: the wave runs to the end wall,
// comes back and meets the paddle, which has finished its stroke. A paddle at rest reflects it
// whole (measured at dp 0.01 in a 0.2 m deep flume: the third pass past the mid gauge is 1.00
// of the second, docs/method/boundaries.md#active-absorption-at-a-piston); an absorbing paddle
// must take at least half of it (the issue's target for AWAS), and its correction must be a real
// stroke (not a zero that passes by accident).
TEST(WaveAbsorption, AbsorbingPaddleTakesTheReturningSolitaryWave) {
  const std::string text = R"(dim: 2
dp: 0.01
physics: {coefsound: 10}
time: {end: 4.6}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1.7, 0.25]}}, layers: 3,
     open: [ymax]}
  - name: paddle
    kind: boundary
    shape: {box: {min: [0.07, 0.0], max: [0.09, 0.22]}}
    walls: outside
    layers: 2
    motion: {type: wave, wave: solitary, depth: 0.1, height: 0.03, absorption: true}
  - {name: water, kind: fluid, shape: {box: {min: [0.10, 0], max: [1.7, 0.1]}}}
gauges:
  - {name: mid, kind: height, at: [0.9, 0.0], sampling: mean}
output: {every: 1.0, vtk: false, gauge_every: 0.01}
)";
  const fs::path dir = fs::path(SWELL_BINARY_DIR) / "test_out" / "wave_absorption";
  fs::remove_all(dir);
  test::run_case_text(text, "absorption.yaml", dir, false, 1);
  const Series mid = read_series_table((dir / "gauges_height.csv").string()).series("mid");
  // Crest of each pass past the mid gauge: incident, reflected by the end wall, re-reflected
  // by the paddle (windows from c = sqrt(g (d + H)) = 1.13 m/s).
  const auto crest = [&](double t0, double t1) {
    double best = -1.0;
    for (std::size_t i = 0; i < mid.t.size(); ++i)
      if (mid.t[i] >= t0 && mid.t[i] < t1) best = std::max(best, mid.v[i] - 0.1);
    return best;
  };
  const double incident = crest(1.0, 2.2), reflected = crest(2.2, 3.6), again = crest(3.6, 4.6);
  std::cout << "crests past the mid gauge: incident " << incident << " m, reflected " << reflected
            << " m, re-reflected " << again << " m (ratio " << again / reflected << ")\n";
  EXPECT_GT(incident, 0.6 * 0.03);
  EXPECT_GT(reflected, 0.5 * incident);
  EXPECT_LT(again, 0.5 * reflected);
}

// A restart while the absorbing paddle's correction is under way continues bitwise: the
// absorber's state (correction, its velocity, the filtered error) is in the checkpoint.
TEST(WaveAbsorption, RestartContinuesBitwise) {
  auto text = [](const char* end) {
    return std::string("dim: 2\ndp: 0.01\nphysics: {coefsound: 10}\ntime: {end: ") + end +
           "}\nbodies:\n"
           "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.5, 0.25]}}, "
           "layers: 3, open: [ymax]}\n"
           "  - {name: paddle, kind: boundary, shape: {box: {min: [0.07, 0.0], max: [0.09, "
           "0.22]}}, walls: outside, layers: 2, motion: {type: wave, wave: regular, depth: 0.1, "
           "height: 0.01, period: 1.0, ramp: 0.1, absorption: {filter: 0.02}}}\n"
           "  - {name: water, kind: fluid, shape: {box: {min: [0.10, 0], max: [0.5, 0.1]}}}\n"
           "output: {every: 0.04, vtk: false}\n";
  };
  const auto [ca, cb] = test::split_run<2>(text("0.16"), text("0.08"), "absorb.yaml",
                                           fs::temp_directory_path() / "swell_awas_full",
                                           fs::temp_directory_path() / "swell_awas_split");
  EXPECT_EQ(ca.clock.steps, cb.clock.steps);
  EXPECT_EQ(ca.particles.pos, cb.particles.pos);
  EXPECT_EQ(ca.particles.vel, cb.particles.vel);
  EXPECT_EQ(ca.particles.rho, cb.particles.rho);
  const auto x = ca.schedule.find("hook.motion.body1.awas.x");
  ASSERT_NE(x, ca.schedule.end());
  EXPECT_GT(std::abs(x->second), 1e-6);  // the correction is moving the paddle
  EXPECT_EQ(x->second, cb.schedule.at("hook.motion.body1.awas.x"));
  EXPECT_EQ(ca.schedule.at("hook.motion.body1.awas.error"),
            cb.schedule.at("hook.motion.body1.awas.error"));
}

TEST(WaveGauge, MeanSamplingIsTheIntervalMean) {
  const std::string text = R"(dim: 2
dp: 0.01
time: {end: 0.8}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.4, 0.2]}}, layers: 3,
     open: [ymax], motion: {type: sinusoidal, amplitude: 0.01, period: 0.5, direction: [1, 0]}}
  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.4, 0.1]}}}
gauges:
  - {name: fine, kind: height, at: [0.05, 0.0], every: 0.002}
  - {name: mean, kind: height, at: [0.05, 0.0], every: 0.1, sampling: mean}
output: {every: 0.4, vtk: false}
)";
  const fs::path dir = fs::path(SWELL_BINARY_DIR) / "test_out" / "wave_gauge_mean";
  fs::remove_all(dir);
  test::run_case_text(text, "mean_gauge.yaml", dir, false, 1);
  const SeriesTable table = read_series_table((dir / "gauges_height.csv").string());
  const Series fine = table.series("fine"), mean = table.series("mean");
  ASSERT_GE(mean.t.size(), 8u);
  double swing = 0.0, worst = 0.0;
  for (std::size_t r = 1; r < mean.t.size(); ++r) {
    const double t0 = mean.t[r - 1], t1 = mean.t[r];
    double sum = 0.0, lo = 1e9, hi = -1e9;
    int n = 0;
    for (std::size_t i = 0; i < fine.t.size(); ++i)
      if (fine.t[i] > t0 && fine.t[i] <= t1)
        sum += fine.v[i], ++n, lo = std::min(lo, fine.v[i]), hi = std::max(hi, fine.v[i]);
    ASSERT_GT(n, 10);
    swing = std::max(swing, hi - lo);
    worst = std::max(worst, std::abs(mean.v[r] - sum / n));
  }
  // The surface swings by millimetres within an interval; the interval means agree to a few
  // percent of that swing (the fine gauge is itself sampled every 2 ms).
  EXPECT_GT(swing, 2e-3);
  EXPECT_LT(worst, 0.05 * swing) << "swing " << swing;
}

}  // namespace
}  // namespace swell
