// `swell compare` and `swell validate`: the comparison of SPH and OpenFOAM runs with each
// other and with experiments (metrics CSV, plots, report.md).
//
//   swell compare RUN_A [RUN_B ...] --reference FILE|RUN [--labels A,B] -o DIR
//       every gauge present in a run and in the reference, against it.
//   swell validate NAME [--run-sph] [--run-foam] [--resolution DP] [--cell-size DX] [-o DIR]
//       the validation case described by validation/NAME/validation.yaml; without --run-* it
//       compares the committed results (validation/NAME/results/<label>/).
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "apps/subcommand.hpp"
#include "validation/metrics.hpp"

namespace swell {

struct CompareOptions {
  std::vector<std::string> runs;    // run folders holding gauges_*.csv
  std::vector<std::string> labels;  // one per run; default: the folder names
  std::string reference;            // a CSV table, or a run folder
  // Legend text of the reference; default: "<method, resolution> (reference)" for a run folder,
  // "<file>, column <column>" for a table.
  std::string reference_label;
  std::string out_dir;
  // gauge=column pairs for reference columns not named after the gauge. Without one, a
  // column named exactly like the gauge, or ending in "_<gauge>", is used.
  std::vector<std::string> map;
  double time_scale = 1.0, value_scale = 1.0;  // applied to the runs (and a reference run)
  Window window;                               // metric window, in scaled time
  std::optional<Window> peak_window;           // default: the metric window
  std::optional<double> arrival_threshold;     // arrival times only when given
};

struct CompareSummary {
  int rows = 0;
  bool plots = false;
  std::string metrics_csv, report;
};

// Throws std::invalid_argument for bad options, std::runtime_error for unreadable files.
CompareSummary run_compare(const CompareOptions& opt, std::ostream& log);

struct ValidateOptions {
  std::string name;         // manifest name, folder or file
  std::string search_root;  // also look for <search_root>/validation/<name>/validation.yaml
  bool run_sph = false, run_foam = false;
  bool save_results = false;        // copy fresh results into the manifest's results folder
  std::vector<double> resolutions;  // SPH dp; default: the manifest's
  std::vector<double> cell_sizes;   // OpenFOAM cell sizes; default: the manifest's
  std::string out_dir;              // default: out/validate/<name>
  int threads = 0;
  int np = 1;                     // OpenFOAM processes
  double end_time = -1.0;         // shorten runs (CI); < 0: the manifest's / case's
  bool progress = true;           // SPH progress line on stderr
  std::vector<std::string> sets;  // --set key.path=value edits of the case (case/reader.hpp)
};

struct ValidateSummary {
  int rows = 0;
  int targets_pass = 0, targets_fail = 0, targets_missing = 0;
  int targets_known_fail = 0;  // of targets_fail: results the target lists in known_failures
  // "<target text>: <run> ..." for each miss not listed as known, and each listed result that
  // meets its target (the list is then out of date).
  std::vector<std::string> unexpected_failures, stale_known_failures;
  bool plots = false;
  std::string metrics_csv, report;
  std::vector<std::string> notes;  // runs missing, OpenFOAM absent, ...
};

// Throws ManifestError / CaseError for bad input, std::runtime_error otherwise.
ValidateSummary run_validate(const ValidateOptions& opt, std::ostream& log);

// "0.004,0.002" -> {0.004, 0.002}; throws std::invalid_argument naming `option`.
std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      bool zero_allowed = false);

// Add `swell compare` and `swell validate` to `app`.
Subcommand add_compare_command(CLI::App& app);
Subcommand add_validate_command(CLI::App& app);

}  // namespace swell
