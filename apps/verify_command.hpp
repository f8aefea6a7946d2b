// `swell verify [NAME...] [-o DIR] [--full] [--list] [-t N]`: runs the verifications of
// verify/registry.cpp (all of them without a NAME) and writes, under DIR (default out/verify):
//   DIR/NAME/<table>.csv    every table of the verification (header = columns, with units)
//   DIR/NAME/<plot>.png     its plots (verify/plot_verify.py; skipped with a message where
//                           python3 with matplotlib is absent), plots.tsv (what was asked)
//   DIR/report.md           per verification: verdict, run time, every figure with its bound
//                           and verdict, the method notes and the plots
// Returns 0 when every figure meets its bound, 1 otherwise (the report says which).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "apps/subcommand.hpp"

namespace swell {

struct VerifyOptions {
  std::vector<std::string> names;  // empty: all
  std::string out_dir = "out/verify";
  bool full = false;
  bool list = false;
  int threads = 1;
};

int run_verify(const VerifyOptions& opt, std::ostream& log);

// Adds `swell verify` to `app`.
Subcommand add_verify_command(CLI::App& app);

}  // namespace swell
