#include "run/ranks.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <memory>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "io/hdf5_file.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/halo.hpp"

namespace swell {

template <int D>
Simulation<D> build_simulation(const CaseSetup<D>& setup, ParticleSet<D> all,
                               const std::map<std::string, double>* saved,
                               const parallel::Comm& comm, long rebalance_every,
                               const RestartRead* read) {
  if (comm.size() == 1) return make_simulation<D>(setup, std::move(all));
  const bool mine_already = read && read->rows && !read->blocks;
  const bool blocks = read && read->blocks;
  // `all`: setup.particles may be moved. (The halo width is a reduction over the ranks where
  // each holds only its own particles.)
  const double width = mine_already || blocks || (setup.distributed && !saved)
                           ? comm.max(halo_width(setup.params, all))
                           : halo_width(setup.params, all);
  const SolverParams& pr = setup.params;
  const int n = comm.size();
  auto get = [&](const std::string& key) {
    const auto it = saved->find(key);
    if (it == saved->end())
      throw std::invalid_argument("checkpoint: no '" + key + "' in its decomposition record");
    return it->second;
  };
  parallel::Slabs slabs;
  ParticleSet<D> mine;
  if (saved && saved->count("decomposition.ranks") &&
      static_cast<int>(saved->at("decomposition.ranks")) == n) {
    slabs.axis = static_cast<int>(get("decomposition.axis"));
    parallel::GatherLayout layout;
    for (int r = 0; r <= n; ++r) {
      slabs.lo.push_back(get("decomposition.lo." + std::to_string(r)));
      if (r == n) break;
      layout.active.push_back(
          static_cast<std::uint64_t>(get("decomposition.active." + std::to_string(r))));
      layout.excluded.push_back(
          static_cast<std::uint64_t>(get("decomposition.excluded." + std::to_string(r))));
    }
    mine = mine_already ? std::move(all) : parallel::share_by_layout(all, layout, comm.rank());
  } else if (blocks) {
    // A block of the checkpoint's rows on each rank (another number of ranks than wrote it):
    // the slabs from the histogram over every rank, the particles to their slab's rank with
    // their file rows, which restore the file's order: the share a whole read would give.
    const int axis = parallel::longest_axis<D>(pr.domain_min.template head<D>(),
                                               pr.domain_max.template head<D>());
    slabs = parallel::balanced_slabs(all, axis, pr.domain_min[axis], pr.domain_max[axis], width,
                                     comm, 4096, 0, true);
    std::vector<std::uint64_t> row(all.size());
    std::iota(row.begin(), row.end(), read->first_row);
    parallel::redistribute(all, slabs, comm, &row);
    mine = std::move(all);
  } else if (setup.distributed && !saved) {
    // Each rank holds its share of a distributed set-up: the same slabs from the histogram
    // over every rank, then the particles travel to their slab's rank and each rank restores
    // the whole set's order (by id, then the set-up's stable cell sort): the share a whole-case
    // set-up would give it, in the same order.
    const double w = width;  // already the maximum over the ranks
    const int axis = parallel::longest_axis<D>(pr.domain_min.template head<D>(),
                                               pr.domain_max.template head<D>());
    slabs = parallel::balanced_slabs(all, axis, pr.domain_min[axis], pr.domain_max[axis], w, comm,
                                     4096, 0, true);
    parallel::redistribute(all, slabs, comm);
    std::vector<std::uint32_t> by_id(all.size());
    std::iota(by_id.begin(), by_id.end(), 0u);
    std::sort(by_id.begin(), by_id.end(),
              [&](std::uint32_t a, std::uint32_t b) { return all.id[a] < all.id[b]; });
    all.permute_in_place(by_id);
    std::vector<std::uint32_t>().swap(by_id);
    const double support = kernel_support_factor(pr.kernel) * pr.h;
    CellGrid<D> order(setup.order_lo.array() - support, setup.order_hi.array() + support, support);
    typename CellGrid<D>::Reorder in_place;
    in_place.in_place = true;
    order.sort(all, in_place);
    mine = std::move(all);
    return make_simulation<D>(
        setup, std::move(mine),
        std::make_unique<parallel::SlabExchange<D>>(comm, slabs, w, rebalance_every));
  } else {
    const int axis = parallel::longest_axis<D>(pr.domain_min.template head<D>(),
                                               pr.domain_max.template head<D>());
    slabs = parallel::balanced_slabs(all, axis, pr.domain_min[axis], pr.domain_max[axis], width,
                                     parallel::Comm::self(), 4096, n, true);
    mine = parallel::share_by_slabs(all, slabs, comm.rank());
  }
  all = ParticleSet<D>();  // the whole set is not kept on any rank
  return make_simulation<D>(
      setup, std::move(mine),
      std::make_unique<parallel::SlabExchange<D>>(comm, slabs, width, rebalance_every));
}

template <int D>
std::string decomposition_report(const Simulation<D>& sim, const parallel::Comm& comm,
                                 double loop_seconds, long loop_steps) {
  const auto* ex = dynamic_cast<const parallel::SlabExchange<D>*>(sim.exchange());
  if (!ex || comm.size() == 1) return {};
  const parallel::HaloStats& h = ex->stats();
  const double n = comm.size(), steps = std::max(1L, loop_steps);
  const double images = comm.sum(static_cast<double>(h.images)) / n / steps;
  const double bytes = comm.sum(static_cast<double>(h.image_bytes)) / n / steps;
  const double migrated = comm.sum(static_cast<double>(h.migrated)) / n / steps;
  const double ex_max = comm.max(h.seconds), ex_mean = comm.sum(h.seconds) / n;
  const double loop_max = comm.max(loop_seconds);
  const auto counts = comm.gather_all(sim.fluid_count());
  std::uint64_t lo = counts.front(), hi = counts.front(), total = 0;
  for (auto c : counts) lo = std::min(lo, c), hi = std::max(hi, c), total += c;
  // Memory per rank: resident now and the peak (the set-up in shares, then the run).
  rusage use{};
  getrusage(RUSAGE_SELF, &use);
  const double now = resident_bytes() / 1048576.0, peak = use.ru_maxrss / 1024.0;
  const double now_lo = comm.min(now), now_hi = comm.max(now);
  const double peak_lo = comm.min(peak), peak_hi = comm.max(peak);
  std::ostringstream o;
  o << std::setprecision(3);
  o << "  decomposition:  " << comm.size() << " ranks, slabs along "
    << "xyz"[ex->slabs().axis] << " (halo width " << ex->width() << " m), rebalanced "
    << h.rebalances << " times\n"
    << "    per rank and step: " << images << " halo images (two builds), " << bytes / 1024.0
    << " KiB received, " << migrated << " particles migrated\n"
    << "    exchange time: " << ex_mean << " s mean, " << ex_max << " s max over ranks, "
    << 100.0 * ex_max / std::max(loop_max, 1e-9) << " % of the time loop\n"
    << "    fluid particles per rank now: " << lo << " - " << hi << " (imbalance "
    << static_cast<double>(hi) * n / std::max<double>(1.0, static_cast<double>(total)) << ")\n"
    << "    memory per rank: " << now_lo << " - " << now_hi << " MiB resident now, peak " << peak_lo
    << " - " << peak_hi << " MiB\n";
  return o.str();
}

bool gather_everything() {
  const char* g = std::getenv("SWELL_GATHER_OUTPUT");
  return g && std::string(g) == "1";
}

bool use_shared_output(const parallel::Comm& comm) {
  if (comm.size() == 1) return false;
  return comm.min(parallel_hdf5() && !gather_everything() ? 1.0 : 0.0) == 1.0;
}

template Simulation<2> build_simulation<2>(const CaseSetup<2>&, ParticleSet<2>,
                                           const std::map<std::string, double>*,
                                           const parallel::Comm&, long, const RestartRead*);
template Simulation<3> build_simulation<3>(const CaseSetup<3>&, ParticleSet<3>,
                                           const std::map<std::string, double>*,
                                           const parallel::Comm&, long, const RestartRead*);
template std::string decomposition_report<2>(const Simulation<2>&, const parallel::Comm&, double,
                                             long);
template std::string decomposition_report<3>(const Simulation<3>&, const parallel::Comm&, double,
                                             long);

}  // namespace swell
