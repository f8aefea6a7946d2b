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
  std::string label;  // legend text: run_display_label() for runs, the reference's label
  std::string file, column;
  double time_scale = 1.0, value_scale = 1.0;
  bool reference = false;  // drawn as markers/black
};
struct PlotSpec {
  std::string png;                    // file name inside the plots folder
  std::string title, xlabel, ylabel;  // axis labels with units (axis_label())
  Window window, peak_window;
  std::vector<PlotLine> lines;
};

// Writes DIR/plots.json and runs plot_validation.py on it with a python that has matplotlib;
// the script writes each PNG and, beside it, an SVG of the same name (a PDF where the SVG would
// exceed 1 MB). Returns false (and says why in `why`) when no such python or script is found or the
// script fails; the PNGs then are not there, and the report says so.
bool make_plots(const std::vector<PlotSpec>& plots, const std::string& plot_dir, std::string* why);

// The python that `make_plots` uses: $SWELL_PYTHON, /usr/bin/python3, python3, whichever
// imports matplotlib first; empty if none does.
std::string find_plot_python();

// Legend and axis text for the plots (issue #17: labels a client report can use).
// A length for a label: "4 mm", "2.86 mm", "0.2 m" (metres in, 3 significant digits).
std::string length_text(double metres);
// A run's legend label from its own run_info.yaml: "SPH dp 4 mm", "interFoam 5 mm cells";
// `fallback` (the folder label) when the kind is unknown.
std::string run_display_label(const RunInfo& info, const std::string& fallback);
// An axis label with its unit: `label` as given when it already has one ("[...]"); otherwise
// "label [unit]" when the series is not scaled (scale 1) and its unit is known, or
// "label [-]" (a normalised, dimensionless quantity).
std::string axis_label(const std::string& label, const std::string& unit, double scale);

// Markdown pieces shared by the two reports.
// The metrics table. Errors of a reference that crosses zero (GaugeMetrics::crosses_zero) are
// written as fractions of its range, "0.031 R", never as percentages; a note under the table
// says so when any row has them.
std::string markdown_metrics_table(const std::vector<MetricRow>& rows);
// The report's plot list: each PNG inline, and its vector copy (SVG, or PDF for a large
// figure) linked beside it; `plot_dir` is where make_plots wrote them, linked as plots/<file>.
std::string markdown_plot_list(const std::vector<PlotSpec>& plots, const std::string& plot_dir);
std::string format_number(double v, int digits = 3);

}  // namespace swell
