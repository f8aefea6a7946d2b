// Shared by the tests that run whole cases through run_case (run/run.hpp): a case
// given as YAML text, run quietly into a folder.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "case/reader.hpp"
#include "io/hdf5_file.hpp"
#include "run/run.hpp"

namespace swell::test {

inline RunSummary run_case_text(const std::string& text, const std::string& label,
                                const std::filesystem::path& dir, bool restart, int threads,
                                bool overwrite = false) {
  const CaseSpec spec = parse_case_text(text, label);
  RunOptions opt;
  opt.out_dir = dir.string();
  opt.progress = false;
  opt.restart = restart;
  opt.overwrite = overwrite;
  opt.threads = threads;
  std::ostringstream log;
  opt.log = &log;
  return run_case(spec, opt);
}

// The restart check: `full` run in one go into folder a (2 threads); into folder b, `half`
// (1 thread), then `full` again with --restart (2 threads). Returns both final checkpoints.
template <int D>
std::pair<Checkpoint<D>, Checkpoint<D>> split_run(const std::string& full, const std::string& half,
                                                  const std::string& label,
                                                  const std::filesystem::path& a,
                                                  const std::filesystem::path& b) {
  std::filesystem::remove_all(a);
  std::filesystem::remove_all(b);
  run_case_text(full, label, a, false, 2);
  run_case_text(half, label, b, false, 1);
  run_case_text(full, label, b, true, 2);
  return {read_checkpoint<D>((a / "checkpoint.h5").string()),
          read_checkpoint<D>((b / "checkpoint.h5").string())};
}

// The whole content of a text file (empty if it cannot be read).
inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace swell::test
