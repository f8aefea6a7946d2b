// `swell waves predict RECORD.csv --paddle COLUMN --depth d --at x1,x2 [--compare P1,P2]`: the
// surface elevation linear wavemaker theory predicts at distances from a paddle, from its
// measured displacement record (waves/record.hpp), and with --compare its agreement with probe
// columns of the same file over a window (RMS error, crest heights, phase lag).
#pragma once

#include <iosfwd>
#include <limits>
#include <string>

#include "apps/subcommand.hpp"

namespace CLI {
class App;
}

namespace swell {

struct WavesPredictOptions {
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();
  std::string file;       // CSV: a time column first, then the paddle (and probe) columns
  std::string paddle;     // displacement column [m]
  std::string at;         // "x1,x2,...": distances from the paddle [m]
  std::string compare;    // "P1,P2,...": probe columns, one per distance
  double depth = kUnset;  // still-water depth at the paddle [m]
  double hinge = kUnset;  // flap: hinge height above the bed [m] (default: a piston)
  double from = kUnset;   // comparison window [s]
  double to = kUnset;
  double fmax = 0.0;  // components above this [Hz] dropped (0: none)
  double gravity = 9.81;
  std::string csv;  // write t and the predictions (and probes) here
};

// Prints the report on `out`; bad input throws std::invalid_argument naming the file or option.
void run_waves_predict(const WavesPredictOptions& opt, std::ostream& out);

// Adds `swell waves predict` to `waves`.
Subcommand add_waves_predict_command(CLI::App& waves);

}  // namespace swell
