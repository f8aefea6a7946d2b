// swell_bench_run: one benchmark measurement in a lean process (no VTK, HDF5 or report code
// loaded), so its peak RSS is the solver's own plus a small runtime. `swell bench` starts it
// for every run; it takes the options of `swell bench --single`.
#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/bench_single.hpp"

int main(int argc, char** argv) {
  CLI::App app{"swell_bench_run: one timed run of a benchmark case (used by `swell bench`)"};
  swell::BenchSingleOptions opt;
  app.add_option("case", opt.case_file, "case file (YAML)")->required();
  app.add_option("--dp", opt.dp, "dp [m] (default: the case's)");
  app.add_option("--end", opt.end, "end time [s] (default: the case's)");
  app.add_option("--steps", opt.steps, "timed steps (instead of running to the end time)");
  app.add_option("--warmup", opt.warmup, "untimed steps before the timed ones");
  app.add_option("-t,--threads", opt.threads, "OpenMP threads");
  CLI11_PARSE(app, argc, argv);
  try {
    return swell::run_bench_single(opt, std::cout);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
