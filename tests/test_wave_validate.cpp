// `swell validate` for wave cases: the first-harmonic amplitude and phase metrics, the paddle
// theory reference (validation/wave_theory.hpp), and a validation folder with a wave case and a
// synthetic result whose amplitude and phase errors are known.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "apps/validate_command.hpp"
#include "case/reader.hpp"
#include "validation/metrics.hpp"
#include "validation/validation_manifest.hpp"
#include "validation/wave_theory.hpp"

namespace fs = std::filesystem;
using namespace swell;

namespace {

constexpr double kPi = std::numbers::pi;
// T = 1 s in d = 0.3 m: L = 1.37295 m from w^2 = g k tanh(k d), g = 9.81 (Newton's method in
// python, independently of waves/; also used by test_foam_waves).
constexpr double kL = 1.37295;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_wave_validate" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

Series sinusoid(double amplitude, double period, double lag, double mean, double t1, double dt) {
  Series s;
  for (double t = 0.0; t <= t1 + 1e-12; t += dt) {
    s.t.push_back(t);
    s.v.push_back(mean + amplitude * std::cos(2 * kPi * (t - lag) / period + 0.7));
  }
  return s;
}

// A piston flume: paddle face at x = 0.13 m, still water 0.3 m, H 0.04 m, T 1 s, no ramp, one
// wave gauge 1 m from the face.
const char* kWaveCase =
    "name: tinywave\ndim: 2\ndp: 0.02\nphysics: {gravity: [0, -9.81]}\ntime: {end: 6.0}\nbodies:\n"
    "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [6, 0.5]}}, open: [ymax]}\n"
    "  - name: paddle\n    kind: boundary\n"
    "    shape: {box: {min: [0.1, 0.0], max: [0.13, 0.45]}}\n    walls: outside\n"
    "    motion: {type: wave, wave: regular, depth: 0.3, height: 0.04, period: 1.0, order: 1,\n"
    "             ramp: 0}\n"
    "  - {name: water, kind: fluid, shape: {box: {min: [0.15, 0], max: [6, 0.3]}}}\n"
    "gauges:\n  - {name: WG1, kind: height, at: [1.13, 0.0]}\n"
    "output: {every: 1.0, gauge_every: 0.01}\n";

}  // namespace

TEST(WaveMetrics, FirstHarmonicAmplitudeAndPhaseLag) {
  const Series ref = sinusoid(0.02, 1.2, 0.0, 0.4, 10.0, 0.01);
  const Series s = sinusoid(0.018, 1.2, 0.06, 0.41, 10.0, 0.01);  // 10 % low, lags 0.05 T
  MetricRequest req;
  req.harmonic_period = 1.2;
  req.harmonic_window = {2.0, 8.0};
  const GaugeMetrics m = compute_metrics(s, ref, req);
  EXPECT_NEAR(m.amplitude, 0.018, 1e-6);
  EXPECT_NEAR(m.ref_amplitude, 0.02, 1e-6);
  EXPECT_NEAR(m.amplitude_error, -0.1, 1e-4);
  EXPECT_NEAR(m.phase_error, 0.05, 1e-4);
  EXPECT_NEAR(metric_value(m, "phase_error"), 0.05, 1e-4);
  // Leading by 0.45 T reads -0.45; lagging by 0.55 T wraps to -0.45 too.
  EXPECT_NEAR(compute_metrics(sinusoid(0.02, 1.2, -0.54, 0.4, 10, 0.01), ref, req).phase_error,
              -0.45, 1e-4);
  EXPECT_NEAR(compute_metrics(sinusoid(0.02, 1.2, 0.66, 0.4, 10, 0.01), ref, req).phase_error,
              -0.45, 1e-4);
  // Not requested: NaN; a window shorter than half a period: NaN.
  EXPECT_TRUE(std::isnan(compute_metrics(s, ref, MetricRequest{}).amplitude));
  req.harmonic_window = {2.0, 2.3};
  EXPECT_TRUE(std::isnan(compute_metrics(s, ref, req).amplitude_error));
}

TEST(WaveTheoryReference, LinearPaddleWaveBehindItsFront) {
  const CaseSpec spec = parse_case_text(kWaveCase, "tinywave.yaml");
  const Series s = paddle_theory_series(spec, "WG1", 0.01, 6.0);
  ASSERT_EQ(s.t.size(), 601u);
  const double k = 2 * kPi / kL, x = 1.0;
  // Group velocity c_g = n c, n = (1 + 2 kd / sinh 2kd) / 2: 1 m at c_g.
  const double kd = k * 0.3, n = 0.5 * (1 + 2 * kd / std::sinh(2 * kd));
  const double arrival = x / (n * kL / 1.0);
  double worst = 0.0;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    const double t = s.t[i];
    if (t < arrival - 0.02) {
      EXPECT_DOUBLE_EQ(s.v[i], 0.3) << t;  // still water ahead of the front
    } else if (t > arrival + 0.02) {
      // eta = H/2 cos(w t - k x), in phase with the paddle's velocity (X = S/2 sin w t).
      worst = std::max(worst, std::abs(s.v[i] - (0.3 + 0.02 * std::cos(2 * kPi * t - k * x))));
    }
  }
  EXPECT_LT(worst, 2e-6);  // L to 6 digits

  CaseSpec no_paddle = spec;
  no_paddle.bodies[1].motion = MotionSpec{};
  EXPECT_THROW(paddle_theory_series(no_paddle, "WG1", 0.01, 6.0), std::invalid_argument);
  EXPECT_THROW(paddle_theory_series(spec, "nope", 0.01, 6.0), std::invalid_argument);
}

// A validation folder with the wave case, the theory reference, and a committed "SPH" result
// 5 % low and 0.03 s (0.03 T) late at WG1: validate reports exactly those errors and judges the
// targets by them.
TEST(WaveValidate, AmplitudeAndPhaseAgainstThePaddleTheory) {
  const fs::path root = scratch("tiny");
  write(root / "cases" / "tinywave.yaml", kWaveCase);
  const fs::path v = root / "validation" / "tinywave";
  const double k = 2 * kPi / kL;
  std::ostringstream csv;
  csv << "# swell gauges, case tinywave\ntime [s],WG1 [m]\n";
  for (int i = 0; i <= 600; ++i) {
    const double t = 0.01 * i;
    csv << t << "," << 0.3 + 0.95 * 0.02 * std::cos(2 * kPi * (t - 0.03) - k * 1.0) << "\n";
  }
  write(v / "results" / "sph_dp0.02" / "gauges_height.csv", csv.str());
  write(v / "results" / "sph_dp0.02" / "run_info.yaml",
        "kind: sph\nresolution: 0.02\nwall_seconds: 10\nsize: 4000\nend_time: 6\n");
  write(v / "validation.yaml",
        "title: tiny wave flume\ncase: ../../cases/tinywave.yaml\n"
        "normalisation:\n  level: {time_scale: 1, value_scale: 1, value_label: \"level [m]\"}\n"
        "references:\n  - {name: theory, theory: paddle, label: \"linear theory\"}\n"
        "gauges:\n  - {gauge: WG1, normalisation: level, reference: {theory: WG1},\n"
        "     window: [2, 6], harmonic: {period: 1.0}}\n"
        "targets:\n"
        "  - {gauge: WG1, against: theory, metric: amplitude_error, max_abs: 0.03, text: H}\n"
        "  - {gauge: WG1, against: theory, metric: phase_error, max_abs: 0.05, text: phase}\n"
        "runs:\n  sph: {resolutions: [0.02]}\n");
  ValidateOptions opt;
  opt.name = "tinywave";
  opt.search_root = root.string();
  opt.out_dir = (root / "out").string();
  std::ostringstream log;
  const ValidateSummary s = run_validate(opt, log);
  EXPECT_EQ(s.rows, 1);
  EXPECT_EQ(s.targets_pass, 1);  // phase 0.03 T
  EXPECT_EQ(s.targets_fail, 1);  // H 5 % low
  ASSERT_EQ(s.unexpected_failures.size(), 1u);
  EXPECT_NE(s.unexpected_failures[0].find("amplitude_error = -0.05"), std::string::npos)
      << s.unexpected_failures[0];
  EXPECT_TRUE(fs::exists(root / "out" / "theory" / "WG1.csv"));
  std::ifstream m(root / "out" / "metrics.csv");
  std::stringstream text;
  text << m.rdbuf();
  EXPECT_NE(text.str().find("phase_error"), std::string::npos);

  // Manifest errors name the key.
  std::string bad = (v / "validation.yaml").string();
  write(bad,
        "title: x\ncase: ../../cases/tinywave.yaml\n"
        "normalisation:\n  level: {time_scale: 1, value_scale: 1}\n"
        "references:\n  - {name: theory, theory: stokes5}\n"
        "gauges:\n  - {gauge: WG1, normalisation: level, reference: {theory: WG1}}\n");
  try {
    load_manifest(bad);
    ADD_FAILURE() << "no error";
  } catch (const ManifestError& e) {
    EXPECT_NE(std::string(e.what()).find("references[0].theory: expected 'paddle'"),
              std::string::npos)
        << e.what();
  }
  write(bad,
        "title: x\ncase: ../../cases/tinywave.yaml\n"
        "normalisation:\n  level: {time_scale: 1, value_scale: 1}\n"
        "references:\n  - {name: theory, theory: paddle}\n"
        "gauges:\n  - {gauge: WG1, normalisation: level, reference: {theory: WG1},\n"
        "     harmonic: {period: -1}}\n");
  try {
    load_manifest(bad);
    ADD_FAILURE() << "no error";
  } catch (const ManifestError& e) {
    EXPECT_NE(std::string(e.what()).find("gauges[0].harmonic.period"), std::string::npos)
        << e.what();
  }
}
