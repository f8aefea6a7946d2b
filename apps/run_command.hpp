// `swell run CASE.yaml [-o OUTDIR] [--restart OUTDIR] [--overwrite] [-t N] [-q] [--set ..]
// [--rebalance N]`: a case run to its end by the run library (run/run.hpp), on one rank or, under
// mpirun, on several.
#pragma once

#include "apps/subcommand.hpp"

namespace swell {

Subcommand add_run_command(CLI::App& app);

}  // namespace swell
