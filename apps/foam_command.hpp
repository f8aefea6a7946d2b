// `swell foam CASE.yaml -o DIR [--cell SIZE] [--cells-per-dp K] [--end T] [--run] [--np N]`:
// writes the interFoam case of a Swell case file and, with --run, runs it and converts its
// probes to gauges_<kind>.csv (foam/foam.hpp). Prints a summary.
#pragma once

#include <iosfwd>

#include "apps/subcommand.hpp"
#include "case/spec.hpp"
#include "foam/foam.hpp"

namespace swell {

// Exit code of `swell foam` when OpenFOAM is not installed (the case is still written).
constexpr int kExitFoamMissing = 4;

// Writes (and with opt.run runs) the case; throws FoamError / std::invalid_argument as
// write_foam_case and run_foam_case do.
FoamResult run_foam_command(const CaseSpec& spec, const FoamOptions& opt, std::ostream& out);

// Adds `swell foam` to `app`.
Subcommand add_foam_command(CLI::App& app);

}  // namespace swell
