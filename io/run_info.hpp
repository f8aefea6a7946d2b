// run_info.yaml: what is known about how the files of a folder were made. `swell run` writes
// it in its output folder (and adds an entry at each restart), `swell validate` next to every
// result it produces, `swell foam` in its case folder, `swell compare` and `swell bench` in
// theirs. Committed validation results carry it too.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "io/provenance.hpp"

namespace swell {

struct RunInfo {
  std::string kind;       // sph | openfoam | compare | validate | bench | fill | "" (unknown)
  double resolution = 0;  // dp or cell size [m]; 0: unknown
  double wall_seconds = std::numeric_limits<double>::quiet_NaN();
  long size = 0;  // particles (SPH) or cells (OpenFOAM)
  double end_time = std::numeric_limits<double>::quiet_NaN();
  std::string date, note;
  // One entry per command that wrote the folder: the first, then each restart.
  std::vector<Provenance> provenance;
  std::string header;  // the first comment line (default: says which command wrote it)
};

// The file's contents; defaults (and no provenance) when it is absent. Throws
// std::runtime_error naming the file for a file that is not valid YAML.
RunInfo read_run_info(const std::string& dir);

// Writes DIR/run_info.yaml (DIR created), atomically.
void write_run_info(const std::string& dir, const RunInfo& info);

// "YYYY-MM-DD HH:MM UTC", the `date` field's format.
std::string utc_minutes_now();

}  // namespace swell
