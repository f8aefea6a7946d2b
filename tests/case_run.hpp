// Shared by the tests that run whole cases through run_case (apps/case_runner.hpp): a case
// given as YAML text, run quietly into a folder.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "apps/case_runner.hpp"
#include "io/case_file.hpp"

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

// The whole content of a text file (empty if it cannot be read).
inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace swell::test
