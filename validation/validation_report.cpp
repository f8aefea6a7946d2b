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

#include "io/resources.hpp"

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

// $SWELL_PLOT_SCRIPT, else validation/plot_validation.py of Swell's data (io/resources).
std::string find_plot_script() {
  if (const char* env = std::getenv("SWELL_PLOT_SCRIPT"); env && fs::exists(env)) return env;
  const auto found = find_data_file("validation/plot_validation.py");
  return found ? found->string() : "";
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
      << "# *_rel_error = |run - ref|/|ref| at the reference samples (mean, max; signed mean);\n"
      << "# crosses_zero = 1: the reference crosses zero in the window (below -"
      << format_number(100.0 * kZeroCrossingTolerance) << " % and above +"
      << format_number(100.0 * kZeroCrossingTolerance) << " % of its\n"
      << "# range R = ref_range): no relative errors (empty), use the *_range_error\n"
      << "# columns = difference / R (mean/max_abs: |run - ref|/R at the reference samples;\n"
      << "# impulse: / (R x impulse window)), given for every row.\n";
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
          "validation/plot_validation.py not found (set SWELL_HOME or SWELL_PLOT_SCRIPT); the "
          "plot specification is in " +
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

std::string length_text(double metres) {
  if (!(metres > 0.0) || !std::isfinite(metres)) return "";
  if (metres < 0.1) return format_number(1000.0 * metres, 3) + " mm";
  return format_number(metres, 3) + " m";
}

std::string run_display_label(const RunInfo& info, const std::string& fallback) {
  const std::string size = length_text(info.resolution);
  if (info.kind == "sph") return size.empty() ? "SPH" : "SPH dp " + size;
  if (info.kind == "openfoam") return size.empty() ? "interFoam" : "interFoam " + size + " cells";
  return fallback;
}

std::string axis_label(const std::string& label, const std::string& unit, double scale) {
  if (label.find('[') != std::string::npos) return label;
  if (scale == 1.0 && !unit.empty()) return label + " [" + unit + "]";
  if (scale == 1.0 && unit.empty()) return label;
  return label + " [-]";
}

std::string markdown_plot_list(const std::vector<PlotSpec>& plots, const std::string& plot_dir) {
  std::ostringstream md;
  for (const auto& p : plots) {
    md << "![" << p.title << "](plots/" << p.png << ")\n\n";
    const fs::path stem = fs::path(p.png).replace_extension();
    for (const char* ext : {".svg", ".pdf"}) {
      const std::string name = stem.string() + ext;
      if (fs::exists(fs::path(plot_dir) / name)) {
        md << "Vector copy: [" << name << "](plots/" << name << ")\n\n";
        break;
      }
    }
  }
  return md.str();
}

std::string markdown_metrics_table(const std::vector<MetricRow>& rows) {
  std::ostringstream md;
  md << "| gauge | run | against | NRMSE | peak | ref. peak | peak err. | peak time err. [s] "
        "| arrival err. [s] | mean err. | max err. |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto pct = [](double v) { return std::isfinite(v) ? format_number(100.0 * v, 3) + " %" : "–"; };
  // A relative error as a percentage, or, where the reference crosses zero, the range-normalised
  // one as a fraction of R.
  auto err = [&](const MetricRow& r, double relative, double over_range) {
    if (!r.m.crosses_zero) return pct(relative);
    return std::isfinite(over_range) ? format_number(over_range, 3) + " R" : std::string("–");
  };
  bool any_crossing = false;
  for (const auto& r : rows) {
    any_crossing = any_crossing || r.m.crosses_zero;
    md << "| " << r.gauge << " | " << r.run << " | " << r.reference << " | "
       << format_number(r.m.rms.nrmse) << " | " << format_number(r.m.peak.value) << " | "
       << format_number(r.m.ref_peak.value) << " | " << err(r, r.m.peak_error, r.m.peak_range_error)
       << " | " << format_number(row_value(r, "peak_time_error_s")) << " | "
       << format_number(row_value(r, "arrival_error_s")) << " | "
       << err(r, r.m.rel.mean_abs, r.m.mean_abs_range_error) << " | "
       << err(r, r.m.rel.max_abs, r.m.max_abs_range_error) << " |\n";
  }
  md << "\nErrors in % are relative (|run - ref| / |ref| at the reference samples; peak: "
        "relative to the reference peak).";
  if (any_crossing)
    md << " Errors marked R are for references that cross zero in the window (below -"
       << format_number(100.0 * kZeroCrossingTolerance) << " % and above +"
       << format_number(100.0 * kZeroCrossingTolerance)
       << " % of their range): a percent error is meaningless there, so the difference is "
          "divided by R, the reference's peak-to-peak range in the window (impulse: by R times "
          "the impulse window).";
  md << "\n";
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
       << err(r, r.m.impulse_error, r.m.impulse_range_error) << " | " << format_number(r.m.mean)
       << " | " << format_number(r.m.ref_mean) << " | "
       << err(r, r.m.mean_error, r.m.mean_range_error) << " | "
       << format_number(r.m.filtered_peak.value) << " | "
       << format_number(r.m.ref_filtered_peak.value) << " | "
       << err(r, r.m.filtered_peak_error, r.m.filtered_peak_range_error) << " |\n";
  }
  return md.str();
}

}  // namespace swell
