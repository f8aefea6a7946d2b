// From run folders and reference tables to the comparison outputs: one metrics row per
// (run, gauge, reference), the metrics CSV, PNG plots through validation/plot_validation.py,
// and a one-page Markdown report. Used by `swell compare` and `swell validate`
// (apps/validate_command.cpp), which decide what is compared with what.
#pragma once

#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

#include "io/run_info.hpp"  // RunInfo, read_run_info, write_run_info
#include "validation/metrics.hpp"
#include "validation/validation_manifest.hpp"

namespace swell {

// A run's gauges as read from its folder.
struct RunData {
  std::string label;
  std::string dir;
  RunInfo info;
  std::vector<Series> gauges;
  const Series* find(const std::string& gauge) const;
};
RunData load_run(const std::string& label, const std::string& dir);

// Copies a run's gauges_*.csv and run_info.yaml into `to` (created; old gauge files removed).
void copy_results(const std::string& from, const std::string& to);

// One row of the metrics table. Metric values are in normalised units; `time_scale` converts
// time differences back to seconds.
struct MetricRow {
  std::string run, kind;
  double resolution = 0.0;
  std::string gauge, reference, reference_label;
  Normalisation norm;
  GaugeMetrics m;
};

// metric_value() plus "<time metric>_s" (peak_time_error_s, arrival_error_s, ...) in seconds.
double row_value(const MetricRow& row, const std::string& metric);

// Writes the metrics CSV: one line per row, every metric of metric_names() and the time errors
// in seconds; '#' header lines say what the columns mean.
void write_metrics_csv(const std::string& path, const std::vector<MetricRow>& rows,
                       const std::string& title);

// One figure: the reference and the runs of one gauge, normalised.
struct PlotLine {
  std::string label, file, column;
  double time_scale = 1.0, value_scale = 1.0;
  bool reference = false;  // drawn as markers/black
};
struct PlotSpec {
  std::string png;  // file name inside the plots folder
  std::string title, xlabel, ylabel;
  Window window, peak_window;
  std::vector<PlotLine> lines;
};

// Writes DIR/plots.json and runs plot_validation.py on it with a python that has matplotlib.
// Returns false (and says why in `why`) when no such python or script is found or the script
// fails; the PNGs then are not there, and the report says so.
bool make_plots(const std::vector<PlotSpec>& plots, const std::string& plot_dir, std::string* why);

// The python that `make_plots` uses: $SWELL_PYTHON, /usr/bin/python3, python3, whichever
// imports matplotlib first; empty if none does.
std::string find_plot_python();

// Markdown pieces shared by the two reports.
std::string markdown_metrics_table(const std::vector<MetricRow>& rows);
std::string format_number(double v, int digits = 3);

}  // namespace swell
