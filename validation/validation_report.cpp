#include "validation/validation_report.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace swell {
namespace {

namespace fs = std::filesystem;

std::string json_string(const std::string& s) {
  return quoted_string(s);
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool python_has_matplotlib(const std::string& python) {
  const std::string cmd = shell_quote(python) + " -c 'import matplotlib, numpy' > /dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

std::string find_plot_script() {
  if (const char* env = std::getenv("SWELL_PLOT_SCRIPT"); env && fs::exists(env)) return env;
  std::vector<fs::path> bases;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    fs::path p = exe.parent_path();
    for (int up = 0; up < 4 && !p.empty(); ++up, p = p.parent_path()) bases.push_back(p);
  }
  bases.push_back(fs::current_path());
  for (const auto& b : bases) {
    const fs::path s = b / "validation" / "plot_validation.py";
    if (fs::exists(s)) return s.string();
  }
  return "";
}

}  // namespace

const Series* RunData::find(const std::string& gauge) const {
  for (const auto& s : gauges)
    if (s.name == gauge) return &s;
  return nullptr;
}

RunData load_run(const std::string& label, const std::string& dir) {
  RunData r;
  r.label = label;
  r.dir = dir;
  r.info = read_run_info(dir);
  r.gauges = read_run_gauges(dir);
  return r;
}

void copy_results(const std::string& from, const std::string& to) {
  fs::create_directories(to);
  for (const auto& e : fs::directory_iterator(to)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("gauges_", 0) == 0 && e.path().extension() == ".csv") fs::remove(e.path());
  }
  for (const auto& e : fs::directory_iterator(from)) {
    const std::string name = e.path().filename().string();
    if ((name.rfind("gauges_", 0) == 0 && e.path().extension() == ".csv") ||
        name == "run_info.yaml")
      fs::copy_file(e.path(), fs::path(to) / name, fs::copy_options::overwrite_existing);
  }
}

double row_value(const MetricRow& row, const std::string& metric) {
  if (metric.size() > 2 && metric.substr(metric.size() - 2) == "_s")
    return metric_value(row.m, metric.substr(0, metric.size() - 2)) / row.norm.time_scale;
  return metric_value(row.m, metric);
}

void write_metrics_csv(const std::string& path, const std::vector<MetricRow>& rows,
                       const std::string& title) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << "# " << title << "\n"
      << "# One row per run, gauge and reference. Values are in the normalised units of the\n"
      << "# row's normalisation (see report.md); *_s columns are time errors in seconds.\n"
      << "# nrmse = RMS(run - ref) / (max ref - min ref) over the reference samples in the "
         "window;\n"
      << "# peak_error = (peak - ref_peak)/|ref_peak|, peaks = maxima in the peak window;\n"
      << "# *_rel_error = |run - ref|/|ref| at the reference samples (mean, max; signed mean).\n";
  out << "run,kind,resolution,gauge,reference,normalisation";
  for (const auto& n : metric_names()) out << "," << n;
  out << ",peak_time_error_s,arrival_error_s\n";
  for (const auto& r : rows) {
    out << r.run << "," << r.kind << "," << json_number(r.resolution) << "," << r.gauge << ","
        << r.reference << "," << r.norm.name;
    for (const auto& n : metric_names()) {
      const double v = metric_value(r.m, n);
      out << ",";
      if (std::isfinite(v)) out << json_number(v);
    }
    for (const char* n : {"peak_time_error_s", "arrival_error_s"}) {
      const double v = row_value(r, n);
      out << ",";
      if (std::isfinite(v)) out << json_number(v);
    }
    out << "\n";
  }
}

std::string find_plot_python() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("SWELL_PYTHON")) candidates.push_back(env);
  candidates.push_back("/usr/bin/python3");
  candidates.push_back("python3");
  for (const auto& p : candidates)
    if (python_has_matplotlib(p)) return p;
  return "";
}

bool make_plots(const std::vector<PlotSpec>& plots, const std::string& plot_dir, std::string* why) {
  fs::create_directories(plot_dir);
  const std::string spec = (fs::path(plot_dir) / "plots.json").string();
  {
    std::ofstream out(spec);
    out << "{\"plots\": [\n";
    for (std::size_t i = 0; i < plots.size(); ++i) {
      const PlotSpec& p = plots[i];
      out << "  {\"png\": " << json_string(p.png) << ", \"title\": " << json_string(p.title)
          << ", \"xlabel\": " << json_string(p.xlabel) << ", \"ylabel\": " << json_string(p.ylabel)
          << ", \"window\": [" << json_number(p.window.t0) << ", " << json_number(p.window.t1)
          << "], \"peak_window\": [" << json_number(p.peak_window.t0) << ", "
          << json_number(p.peak_window.t1) << "],\n   \"lines\": [";
      for (std::size_t k = 0; k < p.lines.size(); ++k) {
        const PlotLine& l = p.lines[k];
        out << (k ? ",\n     " : "\n     ") << "{\"label\": " << json_string(l.label)
            << ", \"file\": " << json_string(fs::absolute(l.file).string())
            << ", \"column\": " << json_string(l.column)
            << ", \"time_scale\": " << json_number(l.time_scale)
            << ", \"value_scale\": " << json_number(l.value_scale)
            << ", \"reference\": " << (l.reference ? "true" : "false") << "}";
      }
      out << "]}" << (i + 1 < plots.size() ? "," : "") << "\n";
    }
    out << "]}\n";
  }
  const std::string python = find_plot_python();
  if (python.empty()) {
    if (why)
      *why =
          "no python3 with matplotlib and numpy (install python3-matplotlib, or set "
          "SWELL_PYTHON); the plot specification is in " +
          spec;
    return false;
  }
  const std::string script = find_plot_script();
  if (script.empty()) {
    if (why)
      *why =
          "validation/plot_validation.py not found (set SWELL_PLOT_SCRIPT); the plot "
          "specification is in " +
          spec;
    return false;
  }
  const std::string log = (fs::path(plot_dir) / "plot.log").string();
  const std::string cmd = shell_quote(python) + " " + shell_quote(script) + " " +
                          shell_quote(spec) + " > " + shell_quote(log) + " 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    if (why) *why = "plot_validation.py failed, see " + log;
    return false;
  }
  return true;
}

std::string format_number(double v, int digits) {
  if (!std::isfinite(v)) return "–";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string markdown_metrics_table(const std::vector<MetricRow>& rows) {
  std::ostringstream md;
  md << "| gauge | run | against | NRMSE | peak | ref. peak | peak err. | peak time err. [s] "
        "| arrival err. [s] | mean rel. err. | max rel. err. |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto pct = [](double v) { return std::isfinite(v) ? format_number(100.0 * v, 3) + " %" : "–"; };
  for (const auto& r : rows) {
    md << "| " << r.gauge << " | " << r.run << " | " << r.reference << " | "
       << format_number(r.m.rms.nrmse) << " | " << format_number(r.m.peak.value) << " | "
       << format_number(r.m.ref_peak.value) << " | " << pct(r.m.peak_error) << " | "
       << format_number(row_value(r, "peak_time_error_s")) << " | "
       << format_number(row_value(r, "arrival_error_s")) << " | " << pct(r.m.rel.mean_abs) << " | "
       << pct(r.m.rel.max_abs) << " |\n";
  }
  // Loads, where a gauge asked for them (impulse, post-impact mean, filtered peak).
  bool loads = false;
  for (const auto& r : rows)
    loads = loads || std::isfinite(r.m.impulse) || std::isfinite(r.m.mean) ||
            std::isfinite(r.m.filtered_peak.value);
  if (!loads) return md.str();
  md << "\n| gauge | run | against | impulse | ref. impulse | impulse err. | mean | ref. mean | "
        "mean err. | filtered peak | ref. filtered peak | filtered peak err. |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    md << "| " << r.gauge << " | " << r.run << " | " << r.reference << " | "
       << format_number(r.m.impulse) << " | " << format_number(r.m.ref_impulse) << " | "
       << pct(r.m.impulse_error) << " | " << format_number(r.m.mean) << " | "
       << format_number(r.m.ref_mean) << " | " << pct(r.m.mean_error) << " | "
       << format_number(r.m.filtered_peak.value) << " | "
       << format_number(r.m.ref_filtered_peak.value) << " | " << pct(r.m.filtered_peak_error)
       << " |\n";
  }
  return md.str();
}

}  // namespace swell
