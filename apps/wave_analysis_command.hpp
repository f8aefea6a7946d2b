// `swell waves analyse FILE.csv --gauge NAME ...`: zero-crossing statistics, harmonic
// amplitudes, the Welch spectrum and its parameters of a gauge column, and with --reflection
// the Mansard-Funke incident/reflected separation of three gauge columns
// (waves/analysis.hpp does the maths).
#pragma once

#include <iosfwd>
#include <limits>
#include <string>
#include <utility>

#include "apps/subcommand.hpp"

namespace CLI {
class App;
}

namespace swell {

struct WavesAnalyseOptions {
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();
  std::string file;                     // gauge CSV
  std::string gauge;                    // column for the single-gauge analysis ("H1" or "H1 [m]")
  double from = kUnset;                 // window start [s] (default: the record's start)
  double to = kUnset;                   // window end [s]
  double period = kUnset;               // fundamental period [s]: enables the harmonic fit
  int harmonics = 3;                    // harmonics fitted
  std::string crossing = "up";          // up | down
  double segment = kUnset;              // Welch segment length [s] (default: 8 segments)
  std::string reflection;               // "G1,G2,G3": three columns for Mansard-Funke
  std::string positions;                // "x1,x2,x3" [m], increasing in the incident direction
  double depth = kUnset;                // water depth [m]
  double fmin = kUnset, fmax = kUnset;  // frequency band [Hz] of the parameters and separation
  double gravity = 9.81;
  std::string csv;  // write the spectrum (and incident/reflected spectra) here
};

// Runs the analysis and prints the report on `out`. Bad input (file, columns, options, a
// record too short for the request) throws std::invalid_argument; a failed write of --csv
// throws std::runtime_error.
void run_waves_analyse(const WavesAnalyseOptions& opt, std::ostream& out);

// The `analyse` subcommand added to a `waves` command. Parsing fills the options it owns; the
// caller runs it after parsing (inside its own error handling) when chosen() is true.
// Adds `swell waves analyse` to `waves`.
Subcommand add_waves_analyse_command(CLI::App& waves);

}  // namespace swell
