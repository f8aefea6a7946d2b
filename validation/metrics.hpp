// Comparison metrics between a computed time series (an SPH or interFoam gauge) and a
// reference series (an experiment, or another run), and the CSV readers that feed them.
//
// Every metric is evaluated on the reference's own sample times inside a window [t0, t1]: the
// computed series is interpolated linearly onto those times, so a densely sampled run is not
// favoured over a sparse table and the reference is never resampled. Both series are in the
// same (usually normalised) units when they get here; see validation/validation_manifest.hpp
// for the per-case normalisation.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "waves/window.hpp"

namespace swell {

// One quantity against time. Values may be NaN (a dry pressure probe, an empty CSV cell).
struct Series {
  std::string name;
  std::string unit;    // as written in the CSV header ("Pa", "m"), empty if none
  std::string source;  // the CSV file it was read from (for plots), empty if built in memory
  std::vector<double> t, v;
};

// A CSV file of series sharing one time column: a swell gauge file
// (`time [s],P1 [Pa],...`, empty cells where a gauge was not due) or a reference table
// (`t_star,p_star_sensor1,...`). Lines starting with '#' are comments.
struct SeriesTable {
  std::string path;
  std::vector<std::string> comments;  // the '#' lines, without the '#'
  std::string time_column;            // first column's name, without its unit
  std::vector<std::string> columns;   // the other columns' names, without units
  std::vector<std::string> units;     // "[unit]" contents per column, "" if none
  std::vector<double> time;
  std::vector<std::vector<double>> values;  // values[column][row]; NaN for empty cells

  // Index of `name` (exact match), or -1.
  int find(const std::string& name) const;
  // The series of column `name` with the rows where it is empty or NaN dropped. Throws
  // std::invalid_argument naming the file and the columns present when it is absent.
  Series series(const std::string& name) const;
};

// Reads a CSV series table. Throws std::runtime_error (file, line) on unreadable files and
// malformed rows. Non-numeric leading columns (a "source" tag) are not supported.
SeriesTable read_series_table(const std::string& path);

// Every gauge series of a run folder: all its gauges_*.csv files. Throws if there are none.
std::vector<Series> read_run_gauges(const std::string& run_dir);

// Linear interpolation of the finite samples of `s` at time `t`; NaN outside their range.
double interpolate(const Series& s, double t);

// Returns `s` with t -> t * time_scale and v -> v * value_scale (normalisation).
Series scaled(const Series& s, double time_scale, double value_scale);

// Normalised RMS error over a window:
//   NRMSE = sqrt(mean_i (s(t_i) - r_i)^2) / (max_i r_i - min_i r_i)
// over the reference samples (t_i, r_i) with t_i in the window and s(t_i) defined (inside the
// computed series' time range, finite). Dividing by the reference's peak-to-peak range makes it
// comparable across gauges (0: identical, ~0.1: visibly different, ~0.5: unrelated).
struct RmsResult {
  int samples = 0;
  double rms = std::numeric_limits<double>::quiet_NaN();
  double range = std::numeric_limits<double>::quiet_NaN();  // reference peak-to-peak
  double nrmse = std::numeric_limits<double>::quiet_NaN();
};
RmsResult rms_error(const Series& s, const Series& ref, Window w);

// The peak inside a window: the largest finite value in [t0, t1] and its time (the first such
// sample on ties). Windows are chosen per gauge to enclose the first impact, so this is "the
// first peak". NaN when the window holds no finite sample.
struct Peak {
  double time = std::numeric_limits<double>::quiet_NaN();
  double value = std::numeric_limits<double>::quiet_NaN();
};
Peak window_peak(const Series& s, Window w);

// Arrival (first wetting): the first time in the window at which the series rises above
// `threshold`, linearly interpolated between the samples either side of the crossing. NaN if
// it never does; the window start if it is already above there.
double arrival_time(const Series& s, double threshold, Window w);

// Relative error at the reference samples in the window: e_i = (s(t_i) - r_i) / |r_i|, for the
// front (Z = x/a) and water levels. mean_abs = mean |e_i|, max_abs = max |e_i| (signed value
// kept in max_signed), mean_signed = mean e_i (positive: the run leads/lies above).
struct RelativeError {
  int samples = 0;
  double mean_abs = std::numeric_limits<double>::quiet_NaN();
  double max_abs = std::numeric_limits<double>::quiet_NaN();
  double max_signed = std::numeric_limits<double>::quiet_NaN();
  double mean_signed = std::numeric_limits<double>::quiet_NaN();
  double max_at = std::numeric_limits<double>::quiet_NaN();  // t_i of max_abs
};
// Reference samples with |r_i| < min_reference are skipped (a dry probe reads 0).
RelativeError relative_error(const Series& s, const Series& ref, Window w,
                             double min_reference = 1e-12);

// Loads (wall pressures and forces), each series on its own samples:
//   integral(s, w)        trapezoidal integral of the finite samples over [t0, t1], the series
//                         interpolated at the window's ends (the impulse of a pressure series);
//   boxcar_peak(s, w, tau) the largest value in w of the moving average over [t - tau/2,
//                         t + tau/2] (a low-pass filter whose response falls to -3 dB at
//                         0.443 / tau), evaluated at the series' sample times in w.
// NaN where the window holds no sample.
double integral(const Series& s, Window w);
Peak boxcar_peak(const Series& s, Window w, double tau);

// Whether a reference crosses zero in a window: its finite samples there reach below
// -tolerance * R and above +tolerance * R, R = max - min (their peak-to-peak range). A percent
// error |run - ref| / |ref| means nothing for such a signal (a wave elevation, an oscillating
// force: the denominator passes through zero), so compute_metrics gives no relative errors for
// it and reports the range-normalised ones (*_range_error) instead. The tolerance keeps a
// pressure record with a little noise below zero (dry probe, cavitation spikes) on the
// relative side.
constexpr double kZeroCrossingTolerance = 0.05;
bool crosses_zero(const Series& ref, Window w, double tolerance = kZeroCrossingTolerance);

// Peak-to-peak range of the finite samples of `s` inside w (NaN when there are none).
double window_range(const Series& s, Window w);

// What to compute for one gauge against one reference.
struct MetricRequest {
  Window window;                   // for NRMSE and the relative errors
  bool peak = false;               // peak value/time against the reference's peak
  Window peak_window;              // window of the (first) peak
  bool arrival = false;            // arrival time against the reference's
  double arrival_threshold = 0.0;  // in the series' (normalised) units
  bool relative = false;           // mean/max relative error
  double min_reference = 1e-12;    // relative errors skip smaller reference values
  bool impulse = false;            // integral over impulse_window, against the reference's
  Window impulse_window;
  bool mean = false;  // time mean over mean_window (integral / duration), where both cover it
  Window mean_window;
  double filter = 0.0;  // > 0: the peak of the boxcar average of this width too
  // > 0: first-harmonic amplitude and phase at this period (normalised time units) by least
  // squares over harmonic_window (waves: wave height and phase against theory or interFoam).
  double harmonic_period = 0.0;
  Window harmonic_window;
};

// All metrics for one series against one reference. Unrequested or undefined entries are NaN.
struct GaugeMetrics {
  RmsResult rms;
  Peak peak, ref_peak;
  double peak_error = std::numeric_limits<double>::quiet_NaN();       // (peak - ref) / |ref|
  double peak_time_error = std::numeric_limits<double>::quiet_NaN();  // peak.time - ref.time
  double arrival = std::numeric_limits<double>::quiet_NaN();
  double ref_arrival = std::numeric_limits<double>::quiet_NaN();
  double arrival_error = std::numeric_limits<double>::quiet_NaN();  // arrival - ref_arrival
  RelativeError rel;
  double impulse = std::numeric_limits<double>::quiet_NaN();
  double ref_impulse = std::numeric_limits<double>::quiet_NaN();
  double impulse_error = std::numeric_limits<double>::quiet_NaN();  // relative
  double mean = std::numeric_limits<double>::quiet_NaN();
  double ref_mean = std::numeric_limits<double>::quiet_NaN();
  double mean_error = std::numeric_limits<double>::quiet_NaN();           // relative
  Peak filtered_peak, ref_filtered_peak;                                  // in peak_window
  double filtered_peak_error = std::numeric_limits<double>::quiet_NaN();  // relative
  // First harmonic at harmonic_period: amplitudes a1 (half the wave height of a sinusoid),
  // amplitude_error = a1 / a1_ref - 1, and phase_error = (phi - phi_ref) / 2 pi in periods,
  // wrapped to [-0.5, 0.5): positive when the series lags the reference.
  double amplitude = std::numeric_limits<double>::quiet_NaN();
  double ref_amplitude = std::numeric_limits<double>::quiet_NaN();
  double amplitude_error = std::numeric_limits<double>::quiet_NaN();
  double phase_error = std::numeric_limits<double>::quiet_NaN();

  // Range-normalised errors: the same differences divided by R, the reference's peak-to-peak
  // range in the metric window (the impulse's by R times the impulse window's length, i.e. the
  // difference of the window means over R). Computed for every signal; for one that crosses
  // zero (crosses_zero) they replace the relative errors above, which are then NaN. The
  // amplitude_error stays relative for every signal: a first-harmonic amplitude is a positive
  // magnitude, never near zero where the signal crosses it.
  bool crosses_zero = false;
  double ref_range = std::numeric_limits<double>::quiet_NaN();             // R
  double mean_abs_range_error = std::numeric_limits<double>::quiet_NaN();  // mean |s - r| / R
  double max_abs_range_error = std::numeric_limits<double>::quiet_NaN();   // max |s - r| / R
  double peak_range_error = std::numeric_limits<double>::quiet_NaN();      // (peak - ref) / R
  double impulse_range_error = std::numeric_limits<double>::quiet_NaN();   // dI / (R T)
  double mean_range_error = std::numeric_limits<double>::quiet_NaN();      // (mean - ref) / R
  double filtered_peak_range_error = std::numeric_limits<double>::quiet_NaN();
};

// First-harmonic amplitude and phase of s at `period` over w (least squares with a mean, as
// fit_harmonics in wave_analysis.hpp): s ~ a0 + a cos(2 pi t / period - phi). NaN amplitude and
// phase when the window holds fewer than 3 samples or less than half a period.
struct FirstHarmonic {
  double amplitude = std::numeric_limits<double>::quiet_NaN();
  double phase = std::numeric_limits<double>::quiet_NaN();  // [rad]
};
FirstHarmonic first_harmonic(const Series& s, double period, Window w);
GaugeMetrics compute_metrics(const Series& s, const Series& ref, const MetricRequest& req);

// Named access for tables and targets: nrmse, rms, peak, ref_peak, peak_time, ref_peak_time,
// peak_error, peak_time_error, arrival, ref_arrival, arrival_error, mean_rel_error,
// max_rel_error, mean_signed_rel_error, samples, impulse, ref_impulse, impulse_error, mean,
// ref_mean, mean_error, filtered_peak, ref_filtered_peak, filtered_peak_error, amplitude,
// ref_amplitude, amplitude_error, phase_error, crosses_zero (1 or 0), ref_range,
// mean_abs_range_error, max_abs_range_error, peak_range_error, impulse_range_error,
// mean_range_error, filtered_peak_range_error. Throws
// std::invalid_argument for other names.
double metric_value(const GaugeMetrics& m, const std::string& name);
const std::vector<std::string>& metric_names();

}  // namespace swell
