// The `swell` command line. Errors from every layer arrive here as exceptions and leave as
// one readable message and a non-zero exit code.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "apps/bench_command.hpp"
#include "apps/fill_command.hpp"
#include "apps/foam_command.hpp"
#include "apps/help_command.hpp"
#include "apps/probe_command.hpp"
#include "apps/run_command.hpp"
#include "apps/subcommand.hpp"
#include "apps/validate_command.hpp"
#include "apps/verify_command.hpp"
#include "apps/waves_command.hpp"
#include "case/reader.hpp"
#include "foam/foam.hpp"
#include "io/hdf5_file.hpp"
#include "io/provenance.hpp"
#include "parallel/comm.hpp"
#include "run/run.hpp"
#include "run/stop_signals.hpp"
#include "solver/time/simulation.hpp"
#include "validation/validation_manifest.hpp"

namespace {

constexpr int kExitInput = 2;     // the case file or the command line is wrong
constexpr int kExitUnstable = 3;  // the run blew up
constexpr int kExitOther = 1;

}  // namespace

int main(int argc, char** argv) {
  // No HDF5 clean-up at exit (it can crash after a failed write), and a file size limit
  // (ulimit -f) makes writes fail with EFBIG, reported like a full disk, instead of killing.
  swell::hdf5_no_atexit();
  std::signal(SIGXFSZ, SIG_IGN);
  // MPI for the process's lifetime when started by mpirun (else nothing). Ranks other than 0
  // print nothing: rank 0 reports for the whole run (its errors, progress and summary).
  swell::parallel::Environment mpi(argc, argv);
  const bool rank0 = swell::parallel::Comm::world().rank() == 0;
  static std::ofstream silent;  // never opened: what is written to it goes nowhere
  if (!rank0) {
    std::cout.rdbuf(silent.rdbuf());
    std::cerr.rdbuf(silent.rdbuf());
  }

  CLI::App app{"Swell: weakly-compressible SPH for coastal and hydraulic engineering"};
  app.require_subcommand(1);
  app.set_version_flag("--version", swell::version_text());

  // Every command registers itself (apps/subcommand.hpp); the order is the help's.
  const std::vector<swell::Subcommand> commands{
      swell::add_run_command(app),      swell::add_fill_command(app),
      swell::add_probe_command(app),    swell::add_compare_command(app),
      swell::add_validate_command(app), swell::add_verify_command(app),
      swell::add_foam_command(app),     swell::add_bench_command(app),
      swell::add_waves_command(app),    swell::add_help_command(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    if (app.get_subcommands().empty()) {
      // No command chosen: say what was wrong, then list the commands.
      const std::string first = argc > 1 ? argv[1] : "";
      if (!first.empty() && first[0] != '-')
        std::cerr << "error: unknown command '" << first << "'\n\n";
      else if (argc > 1)
        std::cerr << "error: " << e.what() << "\n\n";
      else
        std::cerr << "error: a command is required\n\n";
      std::cerr << app.help();
    } else {
      app.exit(e);
    }
    return kExitInput;  // every option error is bad input (exit 2)
  }

  try {
    const swell::Subcommand* chosen = nullptr;
    for (const auto& c : commands)
      if (c.chosen()) chosen = &c;
    // Only `swell run` is decomposed; any other command on several ranks would run N times
    // into the same files.
    if (swell::parallel::Comm::world().size() > 1 && !(chosen && chosen->name() == "run"))
      throw std::invalid_argument(
          "only `swell run` runs on several MPI ranks; start this command without mpirun");
    if (chosen) return chosen->run();
  } catch (const swell::PeerFailed& e) {
    return e.exit_code();  // rank 0 said why
  } catch (const swell::Interrupted& e) {
    std::cerr << "swell: " << e.what() << "\n";
    return e.exit_code();
  } catch (const swell::CaseError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const swell::ManifestError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const swell::FoamError& e) {
    std::cerr << "error: " << e.what() << "\n";
    if (e.kind() == swell::FoamError::Kind::Missing) return swell::kExitFoamMissing;
    return e.kind() == swell::FoamError::Kind::Diverged ? kExitUnstable : kExitOther;
  } catch (const swell::InstabilityError& e) {
    std::cerr << "error: the run went unstable: " << e.what() << "\n";
    return kExitUnstable;
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitOther;
  }
  return 0;
}
