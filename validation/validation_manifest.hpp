// A validation manifest, validation/<NAME>/validation.yaml: which case file, which reference
// data and how its columns map onto the case's gauges, how each quantity is normalised, the
// metric windows, the targets (reported, never tuned to), the resolutions of the SPH and
// OpenFOAM runs and where their committed results live. The format is documented in
// docs/validation/how-it-works.md#manifest. Paths in a manifest are relative to the manifest's
// folder.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "case/spec.hpp"
#include "validation/metrics.hpp"

namespace swell {

// An error in a manifest: what() is "<file>[:<line>]: <key path>: <what is wrong>".
class ManifestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How a gauge's series is made dimensionless before it meets the reference:
// t_norm = t * time_scale, v_norm = v * value_scale.
struct Normalisation {
  std::string name;
  double time_scale = 1.0, value_scale = 1.0;
  std::string time_label = "t [s]", value_label;
};

struct ManifestReference {
  std::string name;   // used by gauges[].reference and targets[].against
  std::string file;   // resolved path of the CSV ("" for a theory reference)
  std::string label;  // legend text
  // "paddle": no file; the series is the case's wave-paddle theory at the gauge named by the
  // column (validation/wave_theory.hpp), computed by `swell validate`.
  std::string theory;
};

// One gauge to compare: its reference columns and the metric windows (normalised time).
struct ManifestGauge {
  std::string gauge;
  std::string normalisation;                   // key into Manifest::normalisations
  std::map<std::string, std::string> columns;  // reference name -> column in that file
  MetricRequest request;
};

// A target from the issue: `metric` of `gauge` against `against` (a reference name, or
// "openfoam": the finest OpenFOAM result) must satisfy the bound, for the runs of `runs`
// (sph | openfoam | all). `known_failures` lists the results (labels of the runs section:
// sph_dp<dp>, foam_dx<size>) known to miss it; the shipped-results test fails on any other
// miss, and on a listed result that meets the target.
struct ManifestTarget {
  std::string gauge, against, metric, runs = "all", text;
  std::optional<double> max, max_abs, min;
  std::vector<std::string> known_failures;
};

struct Manifest {
  std::string file;  // the manifest's path
  std::string dir;   // its folder (paths are relative to it)
  std::string name;  // folder name
  std::string title;
  std::string case_file;               // resolved
  std::string extra_gauges_yaml;       // YAML list appended to the case's gauges ("" if none)
  std::vector<std::string> case_sets;  // `swell validate --set` edits of the case (not in the file)
  std::optional<double> end_time;      // overrides the case's time.end
  std::map<std::string, Normalisation> normalisations;
  std::vector<ManifestReference> references;
  std::vector<ManifestGauge> gauges;
  std::vector<ManifestTarget> targets;
  std::vector<double> sph_resolutions;  // dp [m]
  std::vector<double> foam_cell_sizes;  // [m]
  std::string results_dir;              // resolved; holds <label>/gauges_*.csv
  std::string notes;                    // free text copied into the report

  const ManifestReference* reference(const std::string& name) const;
};

// Reads and checks a manifest. Throws ManifestError naming the file, line and key.
Manifest load_manifest(const std::string& path);

// Finds the manifest for `name`: a path to a manifest file or to its folder, else
// `search_root`/validation/<name>/, else validation/<name>/ of Swell's data (io/resources:
// $SWELL_HOME, the install prefix's share/swell, the source tree). Throws ManifestError listing
// what was tried.
std::string find_manifest(const std::string& name, const std::string& search_root = "");

// The case of a manifest, with the manifest's extra gauges and end time applied, and dp set to
// `dp` when > 0 (geometry is in metres, so dp changes only the particle spacing). Throws
// CaseError (from the case reader) or ManifestError.
CaseSpec load_manifest_case(const Manifest& m, double dp = 0.0, double end_time = -1.0);

// Labels of result folders: sph_dp<dp>, foam_dx<size> (numbers as %g).
std::string sph_label(double dp);
std::string foam_label(double cell_size);

}  // namespace swell
