// `swell waves H T d`: what a regular wave is (length, kd, steepness, Ursell number, regime,
// theory) and the paddle motion that makes it, with warnings where the theory or generation
// order is outside its validity (waves/theory.hpp).
#pragma once

#include <iosfwd>
#include <string>

#include "apps/subcommand.hpp"

namespace swell {

struct WavesOptions {
  double height = 0.0, period = 0.0, depth = 0.0;
  std::string paddle = "piston";  // piston | flap
  double hinge = 0.0;             // flap: hinge height above the bed [m]
  int order = 1;                  // generation order (1, 2)
  double dp = 0.0;                // > 0: resolution checks
  double g = 9.81;
};

// Prints the assessment; returns the number of warnings. Throws std::invalid_argument on bad
// numbers.
int run_waves(const WavesOptions& opt, std::ostream& out);

// Adds `swell waves` to `app`: the theory of `swell waves H T d` and its subcommands analyse,
// predict, goda and target (each registered by its own file); running it runs the chosen one.
Subcommand add_waves_command(CLI::App& app);

}  // namespace swell
