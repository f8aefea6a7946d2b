#include "apps/foam_command.hpp"

#include <filesystem>
#include <iomanip>
#include <ostream>

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

}  // namespace swell
