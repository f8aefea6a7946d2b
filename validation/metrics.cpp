#include "validation/metrics.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace swell {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// "P1 [Pa]" -> {"P1", "Pa"}; "t_star" -> {"t_star", ""}.
std::pair<std::string, std::string> split_unit(const std::string& header) {
  const auto open = header.rfind('[');
  const auto close = header.rfind(']');
  if (open == std::string::npos || close == std::string::npos || close < open)
    return {trim(header), ""};
  return {trim(header.substr(0, open)), trim(header.substr(open + 1, close - open - 1))};
}

double parse_cell(const std::string& cell, const std::string& path, int line) {
  if (cell.empty()) return kNaN;
  if (cell == "nan" || cell == "NaN" || cell == "-nan") return kNaN;
  // strtod, not stod: a denormal such as 6.4e-322 is a valid (tiny) value, not an error.
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  if (end == cell.c_str() || *end != '\0')
    throw std::runtime_error(path + ":" + std::to_string(line) + ": '" + cell +
                             "' is not a number");
  return v;
}

}  // namespace

int SeriesTable::find(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return static_cast<int>(i);
  return -1;
}

Series SeriesTable::series(const std::string& name) const {
  const int c = find(name);
  if (c < 0) {
    std::string have;
    for (const auto& n : columns) have += (have.empty() ? "" : ", ") + n;
    throw std::invalid_argument(path + ": no column '" + name + "' (columns: " + have + ")");
  }
  Series s;
  s.name = name;
  s.unit = units[c];
  s.source = path;
  for (std::size_t r = 0; r < time.size(); ++r) {
    const double v = values[c][r];
    if (!std::isfinite(v) || !std::isfinite(time[r])) continue;
    s.t.push_back(time[r]);
    s.v.push_back(v);
  }
  return s;
}

SeriesTable read_series_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the file");
  SeriesTable table;
  table.path = path;
  std::string line;
  int number = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string text = trim(line);
    if (text.empty()) continue;
    if (text[0] == '#') {
      table.comments.push_back(trim(text.substr(1)));
      continue;
    }
    const auto cells = split_commas(text);
    if (!have_header) {
      if (cells.size() < 2)
        throw std::runtime_error(path + ":" + std::to_string(number) +
                                 ": expected a header 'time,<column>,...'");
      table.time_column = split_unit(cells[0]).first;
      for (std::size_t i = 1; i < cells.size(); ++i) {
        auto [name, unit] = split_unit(cells[i]);
        table.columns.push_back(name);
        table.units.push_back(unit);
      }
      table.values.resize(table.columns.size());
      have_header = true;
      continue;
    }
    if (cells.size() > table.columns.size() + 1)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": " +
                               std::to_string(cells.size()) + " cells, the header has " +
                               std::to_string(table.columns.size() + 1));
    table.time.push_back(parse_cell(cells[0], path, number));
    for (std::size_t c = 0; c < table.columns.size(); ++c)
      table.values[c].push_back(c + 1 < cells.size() ? parse_cell(cells[c + 1], path, number)
                                                     : kNaN);
  }
  if (!have_header) throw std::runtime_error(path + ": no header line (the file holds no data)");
  return table;
}

std::vector<Series> read_run_gauges(const std::string& run_dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(run_dir)) throw std::runtime_error(run_dir + ": not a folder");
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(run_dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("gauges_", 0) == 0 && e.path().extension() == ".csv")
      files.push_back(e.path().string());
  }
  if (files.empty())
    throw std::runtime_error(run_dir + ": no gauges_*.csv files (is this a run's output folder?)");
  std::sort(files.begin(), files.end());
  std::vector<Series> all;
  for (const auto& f : files) {
    const SeriesTable t = read_series_table(f);
    for (const auto& c : t.columns) all.push_back(t.series(c));
  }
  return all;
}

double interpolate(const Series& s, double t) {
  if (s.t.empty() || !(t >= s.t.front()) || !(t <= s.t.back())) return kNaN;
  const auto it = std::upper_bound(s.t.begin(), s.t.end(), t);
  if (it == s.t.end()) return s.v.back();
  const std::size_t i = static_cast<std::size_t>(it - s.t.begin());
  if (i == 0) return s.v.front();
  const double t0 = s.t[i - 1], t1 = s.t[i];
  if (t1 <= t0) return s.v[i];
  const double w = (t - t0) / (t1 - t0);
  return (1.0 - w) * s.v[i - 1] + w * s.v[i];
}

Series scaled(const Series& s, double time_scale, double value_scale) {
  Series out = s;
  for (auto& t : out.t) t *= time_scale;
  for (auto& v : out.v) v *= value_scale;
  return out;
}

RmsResult rms_error(const Series& s, const Series& ref, Window w) {
  RmsResult r;
  double sum = 0.0, lo = kNaN, hi = kNaN;
  for (std::size_t i = 0; i < ref.t.size(); ++i) {
    if (!w.contains(ref.t[i]) || !std::isfinite(ref.v[i])) continue;
    const double v = interpolate(s, ref.t[i]);
    if (!std::isfinite(v)) continue;
    sum += (v - ref.v[i]) * (v - ref.v[i]);
    lo = r.samples == 0 ? ref.v[i] : std::min(lo, ref.v[i]);
    hi = r.samples == 0 ? ref.v[i] : std::max(hi, ref.v[i]);
    ++r.samples;
  }
  if (r.samples == 0) return r;
  r.rms = std::sqrt(sum / r.samples);
  r.range = hi - lo;
  r.nrmse = r.range > 0.0 ? r.rms / r.range : kNaN;
  return r;
}

Peak window_peak(const Series& s, Window w) {
  Peak p;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    if (!w.contains(s.t[i]) || !std::isfinite(s.v[i])) continue;
    if (!std::isfinite(p.value) || s.v[i] > p.value) {
      p.value = s.v[i];
      p.time = s.t[i];
    }
  }
  return p;
}

double arrival_time(const Series& s, double threshold, Window w) {
  bool have_previous = false;
  double t_prev = 0.0, v_prev = 0.0;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    if (!w.contains(s.t[i]) || !std::isfinite(s.v[i])) continue;
    if (s.v[i] > threshold) {
      if (!have_previous) return s.t[i];
      return t_prev + (threshold - v_prev) / (s.v[i] - v_prev) * (s.t[i] - t_prev);
    }
    have_previous = true;
    t_prev = s.t[i];
    v_prev = s.v[i];
  }
  return kNaN;
}

RelativeError relative_error(const Series& s, const Series& ref, Window w, double min_reference) {
  RelativeError r;
  double sum_abs = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < ref.t.size(); ++i) {
    if (!w.contains(ref.t[i]) || !std::isfinite(ref.v[i])) continue;
    if (std::abs(ref.v[i]) < min_reference) continue;
    const double v = interpolate(s, ref.t[i]);
    if (!std::isfinite(v)) continue;
    const double e = (v - ref.v[i]) / std::abs(ref.v[i]);
    sum_abs += std::abs(e);
    sum += e;
    if (r.samples == 0 || std::abs(e) > r.max_abs) {
      r.max_abs = std::abs(e);
      r.max_signed = e;
      r.max_at = ref.t[i];
    }
    ++r.samples;
  }
  if (r.samples > 0) {
    r.mean_abs = sum_abs / r.samples;
    r.mean_signed = sum / r.samples;
  }
  return r;
}

double integral(const Series& s, Window w) {
  // The finite samples inside w, with the interpolated values at its ends (where defined).
  double sum = 0.0, t_prev = kNaN, v_prev = kNaN;
  int n = 0;
  auto add = [&](double t, double v) {
    if (!std::isfinite(v)) return;
    if (n > 0) sum += 0.5 * (v + v_prev) * (t - t_prev);
    t_prev = t, v_prev = v, ++n;
  };
  if (std::isfinite(w.t0)) add(w.t0, interpolate(s, w.t0));
  for (std::size_t i = 0; i < s.t.size(); ++i)
    if (s.t[i] > w.t0 && s.t[i] < w.t1) add(s.t[i], s.v[i]);
  if (std::isfinite(w.t1)) add(w.t1, interpolate(s, w.t1));
  return n >= 2 ? sum : kNaN;
}

Peak boxcar_peak(const Series& s, Window w, double tau) {
  Peak p;
  if (!(tau > 0.0)) return p;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    if (!w.contains(s.t[i])) continue;
    const double lo = s.t[i] - 0.5 * tau, hi = s.t[i] + 0.5 * tau;
    if (lo < s.t.front() || hi > s.t.back()) continue;  // the average needs the whole width
    const double v = integral(s, {lo, hi}) / tau;
    if (std::isfinite(v) && (!std::isfinite(p.value) || v > p.value)) p = {s.t[i], v};
  }
  return p;
}

double window_range(const Series& s, Window w) {
  double lo = kNaN, hi = kNaN;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    if (!w.contains(s.t[i]) || !std::isfinite(s.v[i])) continue;
    lo = std::isfinite(lo) ? std::min(lo, s.v[i]) : s.v[i];
    hi = std::isfinite(hi) ? std::max(hi, s.v[i]) : s.v[i];
  }
  return hi - lo;
}

bool crosses_zero(const Series& ref, Window w, double tolerance) {
  double lo = kNaN, hi = kNaN;
  for (std::size_t i = 0; i < ref.t.size(); ++i) {
    if (!w.contains(ref.t[i]) || !std::isfinite(ref.v[i])) continue;
    lo = std::isfinite(lo) ? std::min(lo, ref.v[i]) : ref.v[i];
    hi = std::isfinite(hi) ? std::max(hi, ref.v[i]) : ref.v[i];
  }
  const double range = hi - lo;
  return range > 0.0 && lo < -tolerance * range && hi > tolerance * range;
}

namespace {
// |s(t_i) - r_i| / range at the reference samples in w: (mean, max).
std::pair<double, double> range_sample_errors(const Series& s, const Series& ref, Window w,
                                              double range) {
  if (!(range > 0.0)) return {kNaN, kNaN};
  double sum = 0.0, max = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < ref.t.size(); ++i) {
    if (!w.contains(ref.t[i]) || !std::isfinite(ref.v[i])) continue;
    const double v = interpolate(s, ref.t[i]);
    if (!std::isfinite(v)) continue;
    const double e = std::abs(v - ref.v[i]) / range;
    sum += e;
    max = std::max(max, e);
    ++n;
  }
  if (n == 0) return {kNaN, kNaN};
  return {sum / n, max};
}

double over_range(double v, double ref, double range) {
  return std::isfinite(v) && std::isfinite(ref) && range > 0.0 ? (v - ref) / range : kNaN;
}

double relative(double v, double ref) {
  return std::isfinite(v) && std::isfinite(ref) && ref != 0.0 ? (v - ref) / std::abs(ref) : kNaN;
}
}  // namespace

GaugeMetrics compute_metrics(const Series& s, const Series& ref, const MetricRequest& req) {
  GaugeMetrics m;
  m.rms = rms_error(s, ref, req.window);
  if (req.peak) {
    m.peak = window_peak(s, req.peak_window);
    m.ref_peak = window_peak(ref, req.peak_window);
    if (std::isfinite(m.peak.value) && std::isfinite(m.ref_peak.value) && m.ref_peak.value != 0.0)
      m.peak_error = (m.peak.value - m.ref_peak.value) / std::abs(m.ref_peak.value);
    m.peak_time_error = m.peak.time - m.ref_peak.time;
  }
  if (req.arrival) {
    m.arrival = arrival_time(s, req.arrival_threshold, req.window);
    m.ref_arrival = arrival_time(ref, req.arrival_threshold, req.window);
    m.arrival_error = m.arrival - m.ref_arrival;
  }
  if (req.relative) m.rel = relative_error(s, ref, req.window, req.min_reference);
  if (req.impulse) {
    m.impulse = integral(s, req.impulse_window);
    m.ref_impulse = integral(ref, req.impulse_window);
    m.impulse_error = relative(m.impulse, m.ref_impulse);
  }
  if (req.mean && !s.t.empty() && !ref.t.empty()) {
    // Over the part of the window both records cover (a run that ends inside the window is
    // averaged over what it has, and the reference over the same times), not divided by a
    // span the records do not reach.
    const Window w{std::max({req.mean_window.t0, s.t.front(), ref.t.front()}),
                   std::min({req.mean_window.t1, s.t.back(), ref.t.back()})};
    if (w.t1 > w.t0) {
      m.mean = integral(s, w) / (w.t1 - w.t0);
      m.ref_mean = integral(ref, w) / (w.t1 - w.t0);
      m.mean_error = relative(m.mean, m.ref_mean);
    }
  }
  if (req.peak && req.filter > 0.0) {
    m.filtered_peak = boxcar_peak(s, req.peak_window, req.filter);
    m.ref_filtered_peak = boxcar_peak(ref, req.peak_window, req.filter);
    m.filtered_peak_error = relative(m.filtered_peak.value, m.ref_filtered_peak.value);
  }
  if (req.harmonic_period > 0.0) {
    const FirstHarmonic a = first_harmonic(s, req.harmonic_period, req.harmonic_window);
    const FirstHarmonic r = first_harmonic(ref, req.harmonic_period, req.harmonic_window);
    m.amplitude = a.amplitude;
    m.ref_amplitude = r.amplitude;
    m.amplitude_error = relative(a.amplitude, r.amplitude);
    double d = (a.phase - r.phase) / (2.0 * M_PI);
    d -= std::floor(d + 0.5);  // to [-0.5, 0.5)
    m.phase_error = d;
  }

  // Range-normalised errors, and no relative ones for a reference that crosses zero.
  m.crosses_zero = crosses_zero(ref, req.window);
  m.ref_range = window_range(ref, req.window);
  const double range = m.ref_range;
  if (req.relative) {
    const auto [mean_abs, max_abs] = range_sample_errors(s, ref, req.window, range);
    m.mean_abs_range_error = mean_abs;
    m.max_abs_range_error = max_abs;
  }
  if (req.peak) m.peak_range_error = over_range(m.peak.value, m.ref_peak.value, range);
  if (req.impulse) {
    const double span = req.impulse_window.t1 - req.impulse_window.t0;
    m.impulse_range_error = over_range(m.impulse, m.ref_impulse, range * span);
  }
  if (req.mean) m.mean_range_error = over_range(m.mean, m.ref_mean, range);
  if (req.peak && req.filter > 0.0)
    m.filtered_peak_range_error =
        over_range(m.filtered_peak.value, m.ref_filtered_peak.value, range);
  if (m.crosses_zero) {
    m.rel = RelativeError{};
    m.peak_error = m.impulse_error = m.mean_error = m.filtered_peak_error = kNaN;
  }
  return m;
}

FirstHarmonic first_harmonic(const Series& s, double period, Window w) {
  FirstHarmonic h;
  std::vector<double> t, v;
  for (std::size_t i = 0; i < s.t.size(); ++i)
    if (w.contains(s.t[i]) && std::isfinite(s.v[i])) t.push_back(s.t[i]), v.push_back(s.v[i]);
  if (t.size() < 3 || !(period > 0.0) || t.back() - t.front() < 0.5 * period) return h;
  const double omega = 2.0 * M_PI / period;
  Eigen::MatrixXd a(static_cast<Eigen::Index>(t.size()), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(t.size()));
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    a(r, 0) = 1.0;
    a(r, 1) = std::cos(omega * t[i]);
    a(r, 2) = std::sin(omega * t[i]);
    b[r] = v[i];
  }
  const Eigen::Vector3d c = a.colPivHouseholderQr().solve(b);
  h.amplitude = std::hypot(c[1], c[2]);
  h.phase = std::atan2(c[2], c[1]);
  return h;
}

const std::vector<std::string>& metric_names() {
  static const std::vector<std::string> names = {"samples",
                                                 "nrmse",
                                                 "rms",
                                                 "peak",
                                                 "ref_peak",
                                                 "peak_error",
                                                 "peak_time",
                                                 "ref_peak_time",
                                                 "peak_time_error",
                                                 "arrival",
                                                 "ref_arrival",
                                                 "arrival_error",
                                                 "mean_rel_error",
                                                 "max_rel_error",
                                                 "mean_signed_rel_error",
                                                 "impulse",
                                                 "ref_impulse",
                                                 "impulse_error",
                                                 "mean",
                                                 "ref_mean",
                                                 "mean_error",
                                                 "filtered_peak",
                                                 "ref_filtered_peak",
                                                 "filtered_peak_error",
                                                 "amplitude",
                                                 "ref_amplitude",
                                                 "amplitude_error",
                                                 "phase_error",
                                                 "crosses_zero",
                                                 "ref_range",
                                                 "mean_abs_range_error",
                                                 "max_abs_range_error",
                                                 "peak_range_error",
                                                 "impulse_range_error",
                                                 "mean_range_error",
                                                 "filtered_peak_range_error"};
  return names;
}

double metric_value(const GaugeMetrics& m, const std::string& name) {
  if (name == "samples") return m.rms.samples;
  if (name == "nrmse") return m.rms.nrmse;
  if (name == "rms") return m.rms.rms;
  if (name == "peak") return m.peak.value;
  if (name == "ref_peak") return m.ref_peak.value;
  if (name == "peak_error") return m.peak_error;
  if (name == "peak_time") return m.peak.time;
  if (name == "ref_peak_time") return m.ref_peak.time;
  if (name == "peak_time_error") return m.peak_time_error;
  if (name == "arrival") return m.arrival;
  if (name == "ref_arrival") return m.ref_arrival;
  if (name == "arrival_error") return m.arrival_error;
  if (name == "mean_rel_error") return m.rel.mean_abs;
  if (name == "max_rel_error") return m.rel.max_abs;
  if (name == "mean_signed_rel_error") return m.rel.mean_signed;
  if (name == "impulse") return m.impulse;
  if (name == "ref_impulse") return m.ref_impulse;
  if (name == "impulse_error") return m.impulse_error;
  if (name == "mean") return m.mean;
  if (name == "ref_mean") return m.ref_mean;
  if (name == "mean_error") return m.mean_error;
  if (name == "filtered_peak") return m.filtered_peak.value;
  if (name == "ref_filtered_peak") return m.ref_filtered_peak.value;
  if (name == "filtered_peak_error") return m.filtered_peak_error;
  if (name == "amplitude") return m.amplitude;
  if (name == "ref_amplitude") return m.ref_amplitude;
  if (name == "amplitude_error") return m.amplitude_error;
  if (name == "phase_error") return m.phase_error;
  if (name == "crosses_zero") return m.crosses_zero ? 1.0 : 0.0;
  if (name == "ref_range") return m.ref_range;
  if (name == "mean_abs_range_error") return m.mean_abs_range_error;
  if (name == "max_abs_range_error") return m.max_abs_range_error;
  if (name == "peak_range_error") return m.peak_range_error;
  if (name == "impulse_range_error") return m.impulse_range_error;
  if (name == "mean_range_error") return m.mean_range_error;
  if (name == "filtered_peak_range_error") return m.filtered_peak_range_error;
  std::string known;
  for (const auto& n : metric_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown metric '" + name + "' (known: " + known + ")");
}

}  // namespace swell
