// `swell waves goda H T h [--h-prime ..] [--d ..] [--hc ..] [--beta ..] ...`: Goda's wave
// pressures on a vertical wall or caisson (waves/goda.hpp): the coefficients, the pressures
// p1..p4 and pu, the horizontal force per metre and its moment about the base, the uplift, and
// the face distribution p(z) (printed, and with --csv written as a table).
#pragma once

#include <iosfwd>
#include <string>
#include <utility>

#include "apps/subcommand.hpp"
#include "waves/goda.hpp"

namespace CLI {
class App;
}

namespace swell {

struct WavesGodaOptions {
  waves::GodaInput input;
  double beta = 0.0;   // [deg]
  std::string lambda;  // "l1,l2,l3"
  std::string csv;     // write the distribution here
};

// Prints the result on `out`. Bad numbers throw std::invalid_argument (naming the option); a
// failed write of --csv throws std::runtime_error.
void run_waves_goda(const WavesGodaOptions& opt, std::ostream& out);

// The `goda` subcommand added to a `waves` command (as `analyse`): parsing fills the options,
// the caller runs it when chosen() is true.
// Adds `swell waves goda` to `waves`.
Subcommand add_waves_goda_command(CLI::App& waves);

}  // namespace swell
