// What the output side of `swell run` reads of a simulation (run/run.cpp): particles,
// pressures, accelerations, clock and exclusion counts. On one rank it is the Simulation
// itself (no copy: the outputs are bitwise what they were). On several ranks (issue #16):
//   - reduce_counts() gives every rank the run's exclusion counts, and the view is a reducer
//     (sum, min, max, max_with) over the ranks: the watchdog and the diagnostics read each
//     rank's own particles (local()) and combine;
//   - with shared output (parallel HDF5), every rank writes its own particles into the
//     snapshots and checkpoints (share(): the counts that place its rows);
//   - gather_region() brings the particles within the gauges' reach to rank 0, for the gauges;
//     gather() brings every rank's particles there, for snapshots and checkpoints where the
//     build has no parallel HDF5;
//   - settle() moves the particles that left their slab to their owners once the outputs of a
//     step are written.
// All of these are collective. A gather costs O(N) on rank 0 (docs/developer/parallel.md).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "io/hdf5_file.hpp"
#include "parallel/comm.hpp"
#include "parallel/decomposition.hpp"
#include "solver/time/simulation.hpp"

namespace swell {

template <int D>
class RunView {
 public:
  // `shared_output`: the ranks write their own particles into snapshots and checkpoints
  // (needs parallel HDF5); else rank 0 writes them from a gather.
  RunView(Simulation<D>& sim, parallel::Comm comm, bool shared_output)
      : sim_(sim), comm_(comm), shared_(shared_output && comm.size() > 1) {}

  bool decomposed() const { return comm_.size() > 1; }
  bool root() const { return comm_.rank() == 0; }
  bool shared_output() const { return shared_; }
  const parallel::Comm& comm() const { return comm_; }
  Simulation<D>& simulation() { return sim_; }

  // Collective on several ranks; nothing on one: the whole state on rank 0 (gather), the run's
  // counts on every rank, then the particles that left their slab to their owners (settle).
  void sync() {
    gather();
    reduce_counts();
    settle();
  }

  // Collective: every rank's particles and accelerations on rank 0 (layout() says where each
  // rank's are).
  void gather() {
    if (!decomposed()) return;
    const Simulation<D>& s = sim_;
    layout_ =
        parallel::gather_to_root<D>(s.particles(), comm_, all_, &s.acceleration(), &ace_, buf_);
  }

  // Collective: the active particles in `region` (the gauges' reach) and their accelerations
  // on rank 0, in the order a whole gather gives them: particles(), pressure() and
  // acceleration() then hold just these. O(particles near the gauges), not O(N).
  template <class Region>
  void gather_region(const Region& region) {
    if (!decomposed()) return;
    const Simulation<D>& s = sim_;
    const ParticleSet<D>& ps = s.particles();
    select_.clear();
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (region.contains(ps, i)) select_.push_back(static_cast<std::uint32_t>(i));
    parallel::gather_selected_to_root<D>(ps, select_, comm_, all_, s.acceleration(), ace_, buf_,
                                         region_counts_);
  }

  // Collective: the particles that left their rank's slab since the last step's sort move to
  // their owners. Called after a step's outputs: the state they saved (a gather or the shared
  // rows) is then exactly the one a restart from it rebuilds (Simulation's first sort migrates
  // the same particles from the same order), so a restart on as many ranks continues bit for
  // bit.
  void settle() {
    if (decomposed()) sim_.redistribute();
  }

  // Collective: this rank's place in a file every rank writes (every rank's counts).
  WriteShare share() const {
    WriteShare w;
    w.rank = comm_.rank();
    const auto& ps = sim_.particles();
    comm_.gather_all(ps.size(), w.active);
    comm_.gather_all(ps.total() - ps.size(), w.excluded);
    return w;
  }

  // Reducer over the ranks (collective; solver/diagnostics.hpp SingleProcess has the same).
  double sum(double x) const { return decomposed() ? comm_.sum(x) : x; }
  double min(double x) const { return decomposed() ? comm_.min(x) : x; }
  double max(double x) const { return decomposed() ? comm_.max(x) : x; }
  template <std::size_t K>
  double max_with(double value, std::array<double, K>& payload) const {
    if (!decomposed()) return value;
    const double m = comm_.max(value);
    const int owner = static_cast<int>(comm_.min(value == m ? comm_.rank() : 1e9));
    payload_.assign(payload.begin(), payload.end());
    if (owner != comm_.rank()) std::fill(payload_.begin(), payload_.end(), 0.0);
    comm_.sum_in_place(payload_);
    std::copy(payload_.begin(), payload_.end(), payload.begin());
    return m;
  }

  // Collective: the run's exclusion counts and faces on every rank (sums, first and last
  // times; the worst density exclusion from the rank that saw the largest ratio).
  void reduce_counts() {
    if (!decomposed()) return;
    const Simulation<D>& s = sim_;
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

  // This rank's own particles, with the run's counts (what the watchdog reads).
  class Local {
   public:
    explicit Local(const RunView& v) : v_(v) {}
    const ParticleSet<D>& particles() const { return v_.sim_.particles(); }
    const SolverParams& params() const { return v_.params(); }
    double time() const { return v_.time(); }
    long steps() const { return v_.steps(); }
    const ExclusionCounts& excluded() const { return v_.excluded(); }
    const FaceExclusions& excluded_faces() const { return v_.excluded_faces(); }
    const typename Simulation<D>::DensityExclusion& worst_density_exclusion() const {
      return v_.worst_density_exclusion();
    }

   private:
    const RunView& v_;
  };
  Local local() const { return Local(*this); }
  // This rank's pressures (valid until the next step).
  const std::vector<double>& local_pressure() { return sim_.pressure(); }

  // The whole run's particles: on rank 0 after a gather (one rank: the simulation's).
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
  bool shared_ = false;
  mutable std::vector<double> payload_;  // max_with's buffer
  std::vector<std::uint32_t> select_;    // gather_region's selection
  std::vector<std::uint64_t> region_counts_;
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
