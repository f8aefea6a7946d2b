#include "apps/foam_command.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <ostream>
#include <vector>

#include "case/reader.hpp"
#include "io/run_info.hpp"

namespace swell {

FoamResult run_foam_command(const CaseSpec& spec, const FoamOptions& opt_in, std::ostream& out) {
  FoamOptions opt = opt_in;
  if (opt.out_dir.empty()) opt.out_dir = "out/" + spec.name + "_foam";
  const Provenance prov = capture_provenance();
  const FoamResult r = opt.run ? run_foam_case(spec, opt, out) : write_foam_case(spec, opt, out);
  RunInfo info;
  info.header = "how this OpenFOAM case was produced (written by swell foam)";
  info.kind = "openfoam";
  info.resolution = r.cell_size;
  info.size = r.cells;
  info.end_time = r.end_time;
  if (r.ran) {
    info.wall_seconds = r.wall_seconds;
    info.note = "interFoam, " + std::to_string(r.steps) + " steps, " +
                std::to_string(opt.np > 1 ? opt.np : 1) + " process(es)";
  } else {
    info.note = "case written, not run";
  }
  info.date = utc_minutes_now();
  info.provenance = {prov};
  write_run_info(r.case_dir, info);
  out << std::defaultfloat << std::setprecision(6);  // the runner's logs may have changed it
  out << "summary: " << r.cells << " cells of " << r.cell_size << " m, end time " << r.end_time
      << " s\n";
  if (r.ran) {
    out << "  interFoam: " << r.steps << " steps in " << std::fixed << std::setprecision(1)
        << r.wall_seconds << " s" << std::defaultfloat << " (" << (opt.np > 1 ? opt.np : 1)
        << " process" << (opt.np > 1 ? "es" : "") << ")\n";
    out << "  gauges: " << r.gauge_dir << "/gauges_<kind>.csv\n";
  } else {
    out << "  case written to " << r.case_dir << "; run it with `swell foam ... --run` or "
        << r.case_dir << "/Allrun\n";
  }
  return r;
}

Subcommand add_foam_command(CLI::App& app) {
  struct Options {
    std::string case_path;
    std::vector<std::string> sets;
    FoamOptions foam;
  };
  auto o = std::make_shared<Options>();
  FoamOptions& foam_opt = o->foam;
  auto* foam = app.add_subcommand(
      "foam", "write an OpenFOAM interFoam case of a case file; --run runs it and converts gauges");
  foam->add_option("case", o->case_path, "case file (YAML)")->required();
  add_set_option(foam, o->sets);
  foam->add_option("-o,--out", foam_opt.out_dir, "case folder (default: out/<case name>_foam)");
  auto* foam_cell =
      foam->add_option("--cell", foam_opt.cell_size, "cell size [m]")->check(positive_check());
  foam->add_option("--cells-per-dp", foam_opt.cells_per_dp, "cell = dp / K (default 1)")
      ->check(positive_check())
      ->excludes(foam_cell);
  foam->add_option("--end", foam_opt.end_time, "end time [s] (default: the case's)")
      ->check(positive_check());
  foam->add_flag("--run", foam_opt.run, "run it (blockMesh ... interFoam) and convert the gauges");
  foam->add_option("--np", foam_opt.np, "processes (decomposePar + mpirun)")->check(count_check());
  return Subcommand(foam, [o] {
    run_foam_command(load_case_file(o->case_path, o->sets), o->foam, std::cout);
    return 0;
  });
}

}  // namespace swell
