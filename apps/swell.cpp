// The `swell` command line. Errors from every layer arrive here as exceptions and leave as
// one readable message and a non-zero exit code.
#include <omp.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "apps/case_runner.hpp"
#include "apps/fill_command.hpp"
#include "apps/probe_command.hpp"
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
  std::string restart_dir;
  run->add_option("--restart", restart_dir,
                  "continue the run in this output folder from its last checkpoint");

  std::string fill_case, fill_out;
  int fill_threads = 0;
  auto* fill = app.add_subcommand(
      "fill", "build a case's particles as `run` would, write <name>_fill.vtp and report");
  fill->add_option("case", fill_case, "case file (YAML)")->required();
  fill->add_option("-o,--out", fill_out, "output folder (default: out/<case name>)");
  fill->add_option("-t,--threads", fill_threads, "OpenMP threads (default: all cores)")
      ->check(CLI::PositiveNumber);

  std::string probe_dir, probe_at, probe_normal, probe_kind = "pressure", probe_out;
  double probe_offset = -1.0;
  auto* probe = app.add_subcommand("probe", "evaluate a gauge on the snapshots of a finished run");
  probe->add_option("outdir", probe_dir, "output folder of a run (holding <case>.h5)")->required();
  probe->add_option("--at", probe_at, "point x,y[,z] (height: horizontal position and line start)")
      ->required();
  probe->add_option("--kind", probe_kind, "pressure | velocity | height")
      ->check(CLI::IsMember({"pressure", "velocity", "height"}));
  probe->add_option("--normal", probe_normal,
                    "pressure: wall normal nx,ny[,nz]; sample at at + offset*normal");
  probe->add_option("--offset", probe_offset, "distance along the normal (default h)");
  probe->add_option("-o,--out", probe_out, "CSV file (default: standard output)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (*run) {
      const swell::CaseSpec spec = swell::load_case_file(case_path);
      swell::RunOptions opt;
      if (!restart_dir.empty()) {
        if (!out_dir.empty() && out_dir != restart_dir)
          throw std::invalid_argument("--restart " + restart_dir + " and -o " + out_dir +
                                      " differ: a restart continues in its own folder");
        out_dir = restart_dir;
        opt.restart = true;
      }
      opt.out_dir = out_dir;
      opt.threads = threads;
      opt.progress = !quiet;
      swell::run_case(spec, opt);
    } else if (*fill) {
      const swell::CaseSpec spec = swell::load_case_file(fill_case);
      swell::FillCommandOptions opt;
      opt.out_dir = fill_out;
      opt.threads = fill_threads;
      swell::run_fill(spec, opt, std::cout);
    } else if (*probe) {
      swell::ProbeOptions opt;
      opt.out_dir = probe_dir;
      opt.kind = probe_kind;
      opt.at = swell::parse_vector_option(probe_at, "--at");
      if (!probe_normal.empty()) opt.normal = swell::parse_vector_option(probe_normal, "--normal");
      if (probe_offset >= 0.0) {
        if (!opt.normal) throw std::invalid_argument("--offset needs --normal");
        opt.offset = probe_offset;
      }
      opt.output = probe_out;
      const int rows = swell::run_probe(opt, std::cout);
      if (!probe_out.empty())
        std::cerr << "probe: " << rows << " snapshots -> " << probe_out << "\n";
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
