// One benchmark measurement (`swell bench --single`, or the lean `swell_bench_run`): builds the
// case's particles (case/setup.hpp), steps it with no output (bench/bench_run.hpp) and prints
// one `bench-result` line. Kept apart from the driver (apps/bench_command) so the lean runner
// links only the solver, the geometry and the case reader.
#pragma once

#include <iosfwd>
#include <string>

namespace swell {

// A single measurement (the child process): the case file at dp (0: the file's), to its end
// time (or `end`), or `steps` steps after `warmup` steps. Prints one `bench-result` line.
struct BenchSingleOptions {
  std::string case_file;
  double dp = 0.0;
  double end = 0.0;
  long steps = 0;
  long warmup = 0;
  int threads = 0;
};

int run_bench_single(const BenchSingleOptions& opt, std::ostream& out);

}  // namespace swell
