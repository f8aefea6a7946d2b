// Comparison metrics on analytic series with known answers: a sine against a shifted and
// scaled sine (NRMSE in closed form, peak shift, peak ratio, arrival shift), relative errors,
// interpolation, and the CSV reader on the gauge and reference formats.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "validation/metrics.hpp"

namespace swell {
namespace {

constexpr double kPi = 3.14159265358979323846;

Series sampled(double (*f)(double, double, double), double a, double b, double t0, double t1,
               double dt) {
  Series s;
  for (double t = t0; t <= t1 + 1e-12; t += dt) {
    s.t.push_back(t);
    s.v.push_back(f(t, a, b));
  }
  return s;
}

// amplitude a, shift b
double shifted_sine(double t, double a, double b) {
  return a * std::sin(2 * kPi * (t - b));
}

TEST(Metrics, InterpolationIsLinearAndNaNOutside) {
  Series s{"x", "", "", {0.0, 1.0, 3.0}, {0.0, 2.0, 0.0}};
  EXPECT_DOUBLE_EQ(interpolate(s, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(interpolate(s, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(interpolate(s, 3.0), 0.0);
  EXPECT_TRUE(std::isnan(interpolate(s, -0.1)));
  EXPECT_TRUE(std::isnan(interpolate(s, 3.1)));
}

TEST(Metrics, NrmseOfShiftedSineMatchesClosedForm) {
  // sin(x - d) - sin(x) has RMS sqrt(2) |sin(d/2)| over whole periods; the reference range is 2.
  const double shift = 0.05;  // period 1
  const Series ref = sampled(shifted_sine, 1.0, 0.0, 0.0, 2.0, 0.001);
  const Series run = sampled(shifted_sine, 1.0, shift, 0.0, 2.0, 0.0007);
  const RmsResult r = rms_error(run, ref, Window{0.0, 2.0});
  const double expected = std::sqrt(2.0) * std::sin(kPi * shift) / 2.0;
  EXPECT_NEAR(r.range, 2.0, 1e-5);
  EXPECT_NEAR(r.nrmse, expected, 2e-3 * expected);
  EXPECT_GT(r.samples, 1900);
  // Identical series: zero.
  EXPECT_NEAR(rms_error(ref, ref, Window{}).nrmse, 0.0, 1e-15);
}

TEST(Metrics, PeakValueAndTimeErrors) {
  // Peak of a sin(2 pi (t - b)) in [0, 1] is at t = 0.25 + b.
  const Series ref = sampled(shifted_sine, 2.0, 0.0, 0.0, 1.0, 0.001);
  const Series run = sampled(shifted_sine, 2.3, 0.04, 0.0, 1.0, 0.001);
  MetricRequest req;
  req.window = Window{0.0, 0.5};  // the positive half wave: a percent error is meaningful
  req.peak = true;
  req.peak_window = Window{0.0, 0.6};
  const GaugeMetrics m = compute_metrics(run, ref, req);
  EXPECT_FALSE(m.crosses_zero);
  EXPECT_NEAR(m.ref_peak.value, 2.0, 1e-6);
  EXPECT_NEAR(m.ref_peak.time, 0.25, 1e-9);
  EXPECT_NEAR(m.peak.time, 0.29, 1e-9);
  EXPECT_NEAR(m.peak_time_error, 0.04, 1e-9);
  EXPECT_NEAR(m.peak_error, 0.15, 1e-6);
  EXPECT_NEAR(metric_value(m, "peak_error"), 0.15, 1e-6);
  // The window decides which peak: the second crest of the run is at 1.29, outside.
  EXPECT_TRUE(std::isnan(window_peak(run, Window{2.0, 3.0}).value));
}

// Loads: the impulse of a sine's half wave is 2A/(2 pi) per unit period, the mean of a
// constant plateau is the plateau, and a spike narrower than the filter width tau reads
// (its area) / tau after the boxcar filter, while its raw peak is its height.
TEST(Metrics, ImpulseMeanAndFilteredPeak) {
  const Series half = sampled(shifted_sine, 3.0, 0.0, 0.0, 1.0, 0.0005);
  EXPECT_NEAR(integral(half, Window{0.0, 0.5}), 3.0 / kPi, 1e-6);
  // Window ends between samples: the series is interpolated there.
  EXPECT_NEAR(integral(half, Window{0.1, 0.4}),
              3.0 / (2 * kPi) * (std::cos(2 * kPi * 0.1) - std::cos(2 * kPi * 0.4)), 1e-6);
  // A plateau of 0.7 from t = 2 to 6 with a triangular spike of height 10, base 0.02 at t = 2.5.
  Series p;
  for (double t = 0.0; t <= 8.0 + 1e-12; t += 0.001) {
    p.t.push_back(t);
    double v = (t >= 2.0 && t <= 6.0) ? 0.7 : 0.0;
    v += std::max(0.0, 10.0 * (1.0 - std::abs(t - 2.5) / 0.01));
    p.v.push_back(v);
  }
  Series ref = p;  // the reference: the same plateau, a spike of height 2 and base 0.1
  for (std::size_t i = 0; i < ref.t.size(); ++i)
    ref.v[i] = (ref.t[i] >= 2.0 && ref.t[i] <= 6.0 ? 0.7 : 0.0) +
               std::max(0.0, 2.0 * (1.0 - std::abs(ref.t[i] - 2.5) / 0.05));
  MetricRequest req;
  req.peak = true;
  req.peak_window = Window{2.2, 3.0};
  req.filter = 0.2;
  req.impulse = true;
  req.impulse_window = Window{2.4, 2.6};
  req.mean = true;
  req.mean_window = Window{3.0, 5.0};
  const GaugeMetrics m = compute_metrics(p, ref, req);
  EXPECT_NEAR(m.peak.value, 10.7, 1e-9);
  EXPECT_NEAR(m.ref_peak.value, 2.7, 1e-9);
  // Both spikes have area 0.1 and lie inside the filter: 0.7 + 0.1 / 0.2 each.
  EXPECT_NEAR(m.filtered_peak.value, 1.2, 1e-6);
  EXPECT_NEAR(m.ref_filtered_peak.value, 1.2, 1e-6);
  EXPECT_NEAR(m.filtered_peak_error, 0.0, 1e-6);
  EXPECT_NEAR(m.impulse, 0.7 * 0.2 + 0.1, 1e-6);
  EXPECT_NEAR(m.ref_impulse, 0.7 * 0.2 + 0.1, 1e-6);
  EXPECT_NEAR(m.mean, 0.7, 1e-9);
  EXPECT_NEAR(metric_value(m, "mean_error"), 0.0, 1e-9);
  // A twice-as-large plateau: mean error +100 % (to half a sample at each end of the doubled
  // span: 0.001 of the 2-unit window).
  Series twice = p;
  for (std::size_t i = 0; i < twice.t.size(); ++i)
    if (twice.t[i] >= 3.0 && twice.t[i] <= 5.0) twice.v[i] *= 2.0;
  EXPECT_NEAR(compute_metrics(twice, ref, req).mean_error, 1.0, 1e-3);
  // A window past the end of the records (a run ending at t = 8 against [3, 10]): the mean over
  // what both cover, [3, 8]: the plateau 0.7 over [3, 6], 0 after, i.e. 0.7 * 3 / 5 = 0.42 (was
  // divided by the window's 7: 0.3).
  req.mean_window = Window{3.0, 10.0};
  const GaugeMetrics past = compute_metrics(p, ref, req);
  EXPECT_NEAR(past.mean, 0.42, 1e-3);
  EXPECT_NEAR(past.ref_mean, 0.42, 1e-3);
  // A window no record reaches: no mean (NaN), not 0.
  req.mean_window = Window{9.0, 10.0};
  EXPECT_TRUE(std::isnan(compute_metrics(p, ref, req).mean));
}

TEST(Metrics, ArrivalTimeIsTheInterpolatedFirstCrossing) {
  // A ramp starting at t = 0.3 with slope 2: it crosses 0.1 at t = 0.35.
  Series s;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.01 * i;
    s.t.push_back(t);
    s.v.push_back(std::max(0.0, 2.0 * (t - 0.3)));
  }
  EXPECT_NEAR(arrival_time(s, 0.1, Window{}), 0.35, 1e-12);
  // Shifted sine: sin crosses 0.5 first at t = 1/12 + shift.
  const Series ref = sampled(shifted_sine, 1.0, 0.0, 0.0, 1.0, 0.0005);
  const Series run = sampled(shifted_sine, 1.0, 0.02, 0.0, 1.0, 0.0005);
  MetricRequest req;
  req.arrival = true;
  req.arrival_threshold = 0.5;
  const GaugeMetrics m = compute_metrics(run, ref, req);
  EXPECT_NEAR(m.ref_arrival, 1.0 / 12.0, 1e-4);
  EXPECT_NEAR(m.arrival_error, 0.02, 1e-4);
  // Never above the threshold: NaN.
  EXPECT_TRUE(std::isnan(arrival_time(ref, 1.5, Window{})));
}

TEST(Metrics, RelativeErrorOfAScaledSeries) {
  // run = 1.1 x ref everywhere: mean and max relative error 10 %, signed +10 %.
  Series ref, run;
  for (int i = 0; i <= 20; ++i) {
    ref.t.push_back(0.1 * i);
    ref.v.push_back(1.0 + 0.1 * i);
    run.t.push_back(0.1 * i);
    run.v.push_back(1.1 * (1.0 + 0.1 * i));
  }
  const RelativeError r = relative_error(run, ref, Window{0.5, 1.5});
  EXPECT_EQ(r.samples, 11);
  EXPECT_NEAR(r.mean_abs, 0.1, 1e-12);
  EXPECT_NEAR(r.max_abs, 0.1, 1e-12);
  EXPECT_NEAR(r.mean_signed, 0.1, 1e-12);
  // A run 10 % low in one sample only: max 10 %, mean 10/11 %.
  Series low = ref;
  low.v[10] *= 0.9;
  const RelativeError l = relative_error(low, ref, Window{0.5, 1.5});
  EXPECT_NEAR(l.max_abs, 0.1, 1e-12);
  EXPECT_NEAR(l.max_signed, -0.1, 1e-12);
  EXPECT_NEAR(l.mean_abs, 0.1 / 11.0, 1e-12);
  EXPECT_NEAR(l.max_at, 1.0, 1e-12);
}

TEST(Metrics, ScalingNormalisesTimeAndValue) {
  Series s{"p", "Pa", "", {0.0, 0.1}, {0.0, 2943.0}};
  const Series n = scaled(s, std::sqrt(9.81 / 0.3), 1.0 / (1000 * 9.81 * 0.3));
  EXPECT_NEAR(n.t[1], 0.1 * std::sqrt(9.81 / 0.3), 1e-12);
  EXPECT_NEAR(n.v[1], 1.0, 1e-12);
}

TEST(Metrics, UnknownMetricNameIsAnError) {
  EXPECT_THROW(metric_value(GaugeMetrics{}, "nrms"), std::invalid_argument);
}

TEST(Metrics, ReadsGaugeAndReferenceCsv) {
  const auto dir = std::filesystem::path(SWELL_BINARY_DIR) / "test_metrics_csv";
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir / "gauges_pressure.csv");
    f << "# swell gauges, case x\n# comment\ntime [s],P1 [Pa],P2 [Pa]\n"
      << "0,1,\n0.001,,5\n0.002,3,nan\n0.003,6.4228534e-322,\n";
  }
  const SeriesTable t = read_series_table((dir / "gauges_pressure.csv").string());
  ASSERT_EQ(t.columns.size(), 2u);
  EXPECT_EQ(t.columns[0], "P1");
  EXPECT_EQ(t.units[1], "Pa");
  EXPECT_EQ(t.comments.size(), 2u);
  const Series p1 = t.series("P1"), p2 = t.series("P2");
  ASSERT_EQ(p1.t.size(), 3u);  // the empty cell is dropped; a denormal is a number
  EXPECT_DOUBLE_EQ(p1.t[1], 0.002);
  ASSERT_EQ(p2.t.size(), 1u);  // empty and nan dropped
  EXPECT_DOUBLE_EQ(p2.v[0], 5.0);
  EXPECT_THROW(t.series("P3"), std::invalid_argument);
  const auto all = read_run_gauges(dir.string());
  EXPECT_EQ(all.size(), 2u);

  // The shipped reference table (provenance comments, plain column names).
  const SeriesTable mm = read_series_table(std::string(SWELL_SOURCE_DIR) +
                                           "/validation/reference/martin_moyce_1952_front.csv");
  EXPECT_EQ(mm.time_column, "T");
  EXPECT_GE(mm.series("Z").t.size(), 10u);

  {
    std::ofstream f(dir / "bad.csv");
    f << "t,x\n0,1\n0.1,abc\n";
  }
  try {
    read_series_table((dir / "bad.csv").string());
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace swell
