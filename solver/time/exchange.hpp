// The domain decomposition as the time loop sees it (issue #16): an Exchange moves particles
// between the ranks of a run and brings each rank the remote particles its pair terms read.
// solver/ knows only this interface; parallel/halo.hpp implements it over MPI slabs. A run
// without one (a single rank) takes none of these calls and is bitwise what it was.
//
// In a step (Simulation::evaluate and step): migrate before each sort (particles that left
// this rank's part go to their owners), build_halo after it (the remote particles within the
// halo width of this rank's part are appended as images after the stored particles, placed in
// the cell grid like periodic images), refresh wherever the periodic images are refreshed
// (the images take their owners' new position, velocity and density), and global reductions
// for the time step and the fluid count. Every call is collective: every rank makes it. With
// periodic axes the Simulation wraps the particles before migrate, and build_halo also builds
// the periodic images (CellGrid::place_remote_images).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

template <int D>
class Exchange {
 public:
  virtual ~Exchange() = default;
  // Once, by the Simulation: its cell grid's domain, cell size and periodic axes (an exchange
  // across a periodic face sends its particles shifted by the period).
  virtual void configure(const CellGrid<D>&) {}
  // Before the sort, periodic images dropped. `step` is the step count (rebalance interval).
  virtual void migrate(ParticleSet<D>& ps, long step) = 0;
  // After the sort: appends the halo images and places them in the grid.
  virtual void build_halo(ParticleSet<D>& ps, CellGrid<D>& grid) = 0;
  // The images' position, velocity and density from their owners' current values.
  virtual void refresh(ParticleSet<D>& ps) = 0;
  // A per-particle vector computed by each rank for its own particles (e.g. shifting's
  // free-surface normals): the images' entries, at [ghost_begin, ...) in image order, from
  // their owners'.
  virtual void refresh_vectors(std::vector<Vec<D>>& field, std::size_t ghost_begin) = 0;
  virtual double global_min(double x) const = 0;
  virtual std::uint64_t global_sum(std::uint64_t x) const = 0;
  virtual double global_max(double x) const = 0;
  // Element-wise sum over the ranks (same length everywhere).
  virtual void global_sum_in_place(std::vector<double>& v) const = 0;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // Checkpoint state (the slab bounds), as named numbers.
  virtual void save(std::map<std::string, double>&) const {}
  virtual void restore(const std::map<std::string, double>&) {}
};

}  // namespace swell
