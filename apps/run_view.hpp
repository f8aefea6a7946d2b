// What the output side of `swell run` reads of a simulation (apps/run_loop.cpp): particles,
// pressures, accelerations, clock and exclusion counts. On one rank it is the Simulation
// itself (no copy: the outputs are bitwise what they were). On several ranks (issue #16)
// sync() gathers every rank's particles and accelerations to rank 0 and reduces the
// exclusion counts, so rank 0's gauges, snapshots, checkpoints, diagnostics and watchdog read
// the whole run as if it ran on one rank. sync() is collective; rank 0 alone reads the view.
// Its cost is one O(N) gather per sync: the limit of this design beyond a few ranks (the
// README, "Several ranks", says how it grows).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "parallel/comm.hpp"
#include "parallel/decomposition.hpp"
#include "solver/time/simulation.hpp"

namespace swell {

template <int D>
class RunView {
 public:
  RunView(Simulation<D>& sim, parallel::Comm comm) : sim_(sim), comm_(comm) {}

  bool decomposed() const { return comm_.size() > 1; }
  bool root() const { return comm_.rank() == 0; }
  const parallel::Comm& comm() const { return comm_; }
  Simulation<D>& simulation() { return sim_; }

  // Collective on several ranks; nothing on one. After the gather, the particles that left
  // their rank's slab since the last step's sort move to their owners: the gathered layout
  // then describes exactly the state a restart from it rebuilds (Simulation's first sort
  // migrates the same particles from the same order), so a restart on the same number of
  // ranks continues bit for bit.
  void sync() {
    if (!decomposed()) return;
    const Simulation<D>& s = sim_;
    layout_ =
        parallel::gather_to_root<D>(s.particles(), comm_, all_, &s.acceleration(), &ace_, buf_);
    sim_.redistribute();
    // Exclusion counts and faces: sums, first and last times; the worst density exclusion
    // from the rank that saw the largest ratio.
    const ExclusionCounts& e = s.excluded();
    excluded_.out_of_domain = comm_.sum(std::uint64_t{e.out_of_domain});
    excluded_.non_finite = comm_.sum(std::uint64_t{e.non_finite});
    excluded_.density_out_of_range = comm_.sum(std::uint64_t{e.density_out_of_range});
    const FaceExclusions& f = s.excluded_faces();
    constexpr double kNone = std::numeric_limits<double>::infinity();
    int last_owner = -1;
    for (int k = 0; k < FaceExclusions::kFaces; ++k) {
      const auto u = static_cast<std::size_t>(k);
      faces_.particles[u] = comm_.sum(std::uint64_t{f.particles[u]});
      faces_.fluid[u] = comm_.sum(std::uint64_t{f.fluid[u]});
      faces_.fluid_mass[u] = comm_.sum(f.fluid_mass[u]);
      const double first = comm_.min(f.first_time[u] < 0.0 ? kNone : f.first_time[u]);
      faces_.first_time[u] = first == kNone ? -1.0 : first;
      faces_.last_time[u] = comm_.max(f.last_time[u]);
      // The last particle lost through the face: from the lowest rank holding that time.
      last_owner = static_cast<int>(
          comm_.min(f.fluid[u] > 0 && f.last_time[u] == faces_.last_time[u] ? comm_.rank() : 1e9));
      const bool mine = last_owner == comm_.rank();
      faces_.last_id[u] = static_cast<std::uint32_t>(comm_.sum(mine ? f.last_id[u] : 0.0));
      for (int d = 0; d < 3; ++d)
        faces_.last_pos[u][static_cast<std::size_t>(d)] =
            comm_.sum(mine ? f.last_pos[u][static_cast<std::size_t>(d)] : 0.0);
    }
    const auto& w = s.worst_density_exclusion();
    const double ratio = comm_.max(w.ratio);
    const int owner =
        static_cast<int>(comm_.min(w.ratio == ratio && ratio > 0.0 ? comm_.rank() : 1e9));
    const bool mine = owner == comm_.rank();
    worst_.ratio = ratio;
    worst_.rho = comm_.sum(mine ? w.rho : 0.0);
    worst_.time = comm_.sum(mine ? w.time : 0.0);
    worst_.id = static_cast<std::uint32_t>(comm_.sum(mine ? double(w.id) : 0.0));
    for (int d = 0; d < D; ++d) worst_.pos[d] = comm_.sum(mine ? w.pos[d] : 0.0);
  }

  const ParticleSet<D>& particles() const { return decomposed() ? all_ : sim_.particles(); }
  const std::vector<Vec<D>>& acceleration() const {
    return decomposed() ? ace_ : sim_.acceleration();
  }
  const std::vector<double>& pressure() {
    if (!decomposed()) return sim_.pressure();
    const TaitEos eos(sim_.params().rho0, sim_.params().c0, sim_.params().gamma);
    press_.resize(all_.total());
    for (std::size_t i = 0; i < all_.size(); ++i) press_[i] = eos.pressure(all_.rho[i]);
    return press_;
  }
  const ExclusionCounts& excluded() const { return decomposed() ? excluded_ : sim_.excluded(); }
  const FaceExclusions& excluded_faces() const {
    return decomposed() ? faces_ : sim_.excluded_faces();
  }
  const typename Simulation<D>::DensityExclusion& worst_density_exclusion() const {
    return decomposed() ? worst_ : sim_.worst_density_exclusion();
  }
  // The clock with the run's exclusion counts (every rank's).
  SimulationClock clock() const {
    SimulationClock c = sim_.clock();
    c.excluded = excluded();
    return c;
  }
  const parallel::GatherLayout& layout() const { return layout_; }
  double time() const { return sim_.time(); }
  long steps() const { return sim_.steps(); }
  double dt() const { return sim_.dt(); }
  const SolverParams& params() const { return sim_.params(); }

 private:
  Simulation<D>& sim_;
  parallel::Comm comm_;
  ParticleSet<D> all_;
  std::vector<Vec<D>> ace_;
  std::vector<double> press_;
  parallel::GatherBuffers buf_;
  parallel::GatherLayout layout_;
  ExclusionCounts excluded_;
  FaceExclusions faces_;
  typename Simulation<D>::DensityExclusion worst_;
};

}  // namespace swell
