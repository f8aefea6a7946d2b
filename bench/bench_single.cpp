// One benchmark measurement: see bench/bench_single.hpp.
#include "bench/bench_single.hpp"

#include <omp.h>

#include <iomanip>
#include <ostream>

#include "bench/bench_run.hpp"
#include "case/reader.hpp"
#include "case/setup.hpp"

namespace swell {
namespace {

template <int D>
bench::RunResult single_dim(const CaseSpec& spec, const BenchSingleOptions& opt) {
  CaseSetup<D> setup = setup_case<D>(spec);
  Simulation<D> sim = make_simulation<D>(setup, std::move(setup.particles));
  if (opt.steps > 0) {
    for (long s = 0; s < opt.warmup; ++s) sim.step();
    return bench::time_run(sim, 0.0, opt.steps);
  }
  return bench::time_run(sim, spec.t_end, 0);
}

}  // namespace

int run_bench_single(const BenchSingleOptions& opt, std::ostream& out) {
  const long rss_base = bench::proc_status_kb("VmRSS");
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  CaseSpec spec = load_case_file(opt.case_file);
  if (opt.dp > 0.0) spec.dp = opt.dp;
  if (opt.end > 0.0) spec.t_end = opt.end;
  const bench::RunResult r = spec.dim == 2 ? single_dim<2>(spec, opt) : single_dim<3>(spec, opt);
  const long rss_peak = bench::proc_status_kb("VmHWM");
  out << std::setprecision(9) << "bench-result particles=" << r.particles << " fluid=" << r.fluid
      << " steps=" << r.steps << " sim_time=" << r.sim_time << " wall=" << r.wall
      << " pss=" << r.particle_steps_per_second() << " neighbour=" << r.phases.neighbour
      << " interaction=" << r.phases.interaction << " integration=" << r.phases.integration
      << " other=" << r.other << " threads=" << omp_get_max_threads() << " rss_base_kb=" << rss_base
      << " rss_peak_kb=" << rss_peak << "\n";
  return 0;
}

}  // namespace swell
