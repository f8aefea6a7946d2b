// `swell probe OUTDIR --at x,y[,z]`: evaluates a pressure, velocity or water-height gauge on
// the snapshots saved in OUTDIR/<name>.h5, with the same code as the in-run gauges.
#pragma once

#include <Eigen/Core>
#include <iosfwd>
#include <optional>
#include <string>

#include "apps/subcommand.hpp"

namespace swell {

struct ProbeOptions {
  std::string out_dir;            // a run's output folder
  std::string kind = "pressure";  // pressure | velocity | height | runup
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> normal;  // pressure: sample at at + offset * normal
  std::optional<double> offset;
  std::optional<double> size;         // pressure: a sensor face of this size (needs `normal`)
  std::optional<Eigen::Vector3d> to;  // runup: the line's upper end (`at` is its lower end)
  std::optional<double> swl;          // runup: still-water level
  std::string output;                 // CSV file; empty: write to `out`
};

// Writes the CSV series (header with units, one row per snapshot); returns the row count.
int run_probe(const ProbeOptions& opt, std::ostream& out);

// Parses "x,y" or "x,y,z" (a command-line vector). Throws std::invalid_argument.
Eigen::Vector3d parse_vector_option(const std::string& text, const std::string& option);

// Adds `swell probe` to `app`.
Subcommand add_probe_command(CLI::App& app);

}  // namespace swell
