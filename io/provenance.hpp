// How an output was made: the one record every command writes next to its results
// (run_info.yaml, run_summary.txt, the HDF5 run file's root attributes, '#' lines of CSV
// files, VTK field data). Built once per command by capture_provenance().
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace swell {

struct Provenance {
  std::string version;    // SWELL_VERSION
  std::string commit;     // git commit of the build (+ "-dirty"), "unknown" without git
  std::string compiler;   // e.g. "GNU 12.2.0"
  std::string build;      // build type and flags, e.g. "Release: -O3 -DNDEBUG ... -march=native"
  std::string command;    // the process's command line, arguments shell-quoted
  int threads = 0;        // OpenMP threads the command runs with
  int ranks = 1;          // MPI ranks (`swell run` under mpirun sets it)
  std::string date;       // start, UTC ISO 8601 (2026-12-02T17:40:12Z)
  std::string host;       // host name
  std::string cpu;        // /proc/cpuinfo "model name" (as lscpu shows), "unknown" if absent
  std::string recovered;  // non-empty: reconstructed afterwards (e.g. from git history)

  // Every field as (key, text), in a fixed order; the one list the writers iterate.
  std::vector<std::pair<std::string, std::string>> fields() const;
};

// The record of this process now: build constants, /proc/self/cmdline, omp_get_max_threads(),
// the current UTC time, gethostname() and /proc/cpuinfo. Call it after the thread count is set.
Provenance capture_provenance();

// `swell --version`: "swell 0.2.0 (commit <id>; GNU 12.2.0; Release: <flags>)".
std::string version_text();

// `key: value` lines (YAML block mapping) indented by `indent` spaces; strings double-quoted.
std::string provenance_yaml(const Provenance& p, int indent);

// Aligned "key: value" lines for text reports, each prefixed by `prefix` (e.g. "  " or "# ").
std::string provenance_text(const Provenance& p, const std::string& prefix);

// `s` in double quotes, with `"`, `\` and newlines escaped (valid YAML and JSON).
std::string quoted_string(const std::string& s);

// The command line of this process (/proc/self/cmdline), arguments with spaces or shell
// characters single-quoted; "unknown" where /proc is not readable.
std::string process_command_line();

}  // namespace swell
