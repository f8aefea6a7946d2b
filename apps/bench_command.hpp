// `swell bench`: the performance benchmark of issue #5. Runs the fixed cases of bench/cases/
// (B2D, B3D at dp 0.02 and 0.015) with 1 and 2 threads, several times each, every run in a
// fresh `swell bench --single` process so its peak RSS is its own; reports medians of
// particle-steps per second, steps, phase times and memory next to the DualSPHysics 5.4 CPU
// figures for the same cases, and optionally a scaling sweep of B3D over dp (CSV + PNG).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "apps/subcommand.hpp"
#include "bench/bench_single.hpp"  // `swell bench --single`

namespace swell {

struct BenchOptions {
  std::vector<std::string> cases;  // b2d, b3d, b3d_fine (default: all three)
  std::vector<int> threads{1, 2};
  int repeats = 3;
  bool sweep = false;
  std::vector<double> sweep_dp;  // default: N from ~1e4 to ~1e6
  long sweep_steps = 40;         // steps per sweep point (after `sweep_warmup`)
  long sweep_warmup = 10;
  std::string out_dir = "out/bench";
  std::string bench_dir;  // folder holding cases/*.yaml (default: found from the executable)
};

int run_bench(const BenchOptions& opt, std::ostream& log);

// Adds `swell bench` to `app`.
Subcommand add_bench_command(CLI::App& app);

}  // namespace swell
