#include "apps/run_command.hpp"

#include <CLI/CLI.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "case/reader.hpp"
#include "parallel/comm.hpp"
#include "run/run.hpp"
#include "run/stop_signals.hpp"

namespace swell {
namespace {

struct RunCommandOptions {
  std::string case_path, out_dir, restart_dir;
  int threads = 0;
  bool quiet = false, overwrite = false;
  std::vector<std::string> sets;
  long rebalance_every = 100;
};

int run_command(RunCommandOptions o) {
  // Under mpirun every rank runs the case on its slab; a build without MPI cannot.
  if (const int ranks = parallel::launcher_world_size();
      ranks > 1 && parallel::Comm::world().size() != ranks)
    throw std::invalid_argument(
        "swell run: started on " + std::to_string(ranks) +
        " MPI ranks, but this swell was built without MPI (install libopenmpi-dev and "
        "rebuild; scripts/setup does); run one rank, with OpenMP threads (-t N)");
  const CaseSpec spec = load_case_file(o.case_path, o.sets);
  RunOptions opt;
  if (!o.restart_dir.empty()) {
    if (!o.out_dir.empty() && o.out_dir != o.restart_dir)
      throw std::invalid_argument("--restart " + o.restart_dir + " and -o " + o.out_dir +
                                  " differ: a restart continues in its own folder");
    o.out_dir = o.restart_dir;
    opt.restart = true;
  }
  opt.out_dir = o.out_dir;
  opt.overwrite = o.overwrite;
  opt.threads = o.threads;
  opt.progress = !o.quiet && parallel::Comm::world().rank() == 0;
  opt.rebalance_every = o.rebalance_every;
  install_stop_handlers();
  run_case(spec, opt);
  return 0;
}

}  // namespace

Subcommand add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunCommandOptions>();
  auto* run = app.add_subcommand("run", "run a case file to its end time");
  run->add_option("case", o->case_path, "case file (YAML)")->required();
  run->add_option("-o,--out", o->out_dir, "output folder (default: out/<case name>)");
  run->add_option("-t,--threads", o->threads, "OpenMP threads (default: all cores)")
      ->check(count_check());
  run->add_flag("-q,--quiet", o->quiet, "no progress line");
  add_set_option(run, o->sets);
  auto* restart_opt =
      run->add_option("--restart", o->restart_dir,
                      "continue the run in this output folder from its last checkpoint");
  run->add_option("--rebalance", o->rebalance_every,
                  "under mpirun: balance the slabs by the pair loop's estimated work every N steps "
                  "(0: never)")
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--overwrite", o->overwrite,
                "replace the run the output folder already holds (else such a folder is refused)")
      ->excludes(restart_opt);
  return Subcommand(run, [o] { return run_command(*o); });
}

}  // namespace swell
