// `swell waves target CASE.yaml --at x1,x2 --end T [--every dt] [--csv FILE]`: the wave a case's
// wavemaker is meant to make, at distances from the paddle: the target surface elevation its
// signal carries (waves/wavemaker.hpp: linear components, Stokes' bound second harmonic of a
// second-order regular wave, the bound long wave of a second-order sea, a soliton), ramped as
// the motion law ramps the paddle, and the second-order bound part alone, on the case's clock.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "apps/subcommand.hpp"

namespace CLI {
class App;
}

namespace swell {

struct WavesTargetOptions {
  std::string case_file;
  std::vector<std::string> sets;  // --set edits, as `swell run`
  std::string body;               // the wavemaker body (default: the first with a wave motion)
  std::string at;                 // "x1,x2,...": distances from the paddle's rest face [m]
  double end = 0.0;               // last time [s] on the case's clock
  double every = 0.01;            // sampling interval [s]
  std::string csv;                // write here (default: print)
};

// Writes the CSV (time, then eta and eta_bound per distance) to opt.csv or `out`; bad input
// throws std::invalid_argument or CaseError naming the file, body or option.
void run_waves_target(const WavesTargetOptions& opt, std::ostream& out);

// Adds `swell waves target` to `waves`.
Subcommand add_waves_target_command(CLI::App& waves);

}  // namespace swell
