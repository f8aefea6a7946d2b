// The `swell` command line. Errors from every layer arrive here as exceptions and leave as
// one readable message and a non-zero exit code.
#include <omp.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "apps/case_runner.hpp"
#include "io/case_file.hpp"
#include "solver/simulation.hpp"

namespace {

constexpr int kExitInput = 2;     // the case file or the command line is wrong
constexpr int kExitUnstable = 3;  // the run blew up
constexpr int kExitOther = 1;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Swell: weakly-compressible SPH for coastal and hydraulic engineering"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("swell ") + "0.1.0");

  std::string case_path, out_dir;
  int threads = 0;
  bool quiet = false;
  auto* run = app.add_subcommand("run", "run a case file to its end time");
  run->add_option("case", case_path, "case file (YAML)")->required();
  run->add_option("-o,--out", out_dir, "output folder (default: out/<case name>)");
  run->add_option("-t,--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::PositiveNumber);
  run->add_flag("-q,--quiet", quiet, "no progress line");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (*run) {
      const swell::CaseSpec spec = swell::load_case_file(case_path);
      swell::RunOptions opt;
      opt.out_dir = out_dir;
      opt.threads = threads;
      opt.progress = !quiet;
      swell::run_case(spec, opt);
    }
  } catch (const swell::CaseError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
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
