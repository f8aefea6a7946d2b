// The time loop of one WCSPH run: neighbour sort, interaction, time step and integrator.
//
// Simulation owns the particles and every buffer the loop needs; after construction a step
// allocates nothing. Output and gauges read particles() between steps.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "solver/cell_grid.hpp"
#include "solver/interaction.hpp"
#include "solver/particle_set.hpp"
#include "solver/physics_terms.hpp"
#include "solver/solver_params.hpp"

namespace swell {

// Thrown when the run cannot go on (time step collapse, every fluid particle lost).
class InstabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExclusionCounts {
  std::size_t out_of_domain = 0;
  std::size_t non_finite = 0;
  std::size_t density_out_of_range = 0;
  std::size_t total() const { return out_of_domain + non_finite + density_out_of_range; }
};

struct PhaseTimes {
  double neighbour = 0.0;    // cell sort and reordering [s]
  double interaction = 0.0;  // pressure, pair loop and time-step reductions [s]
  double integration = 0.0;  // predictor/corrector updates [s]
};

template <int D>
class Simulation {
 public:
  Simulation(const SolverParams& params, ParticleSet<D> particles);

  // Advances by one (variable) time step.
  void step();

  double time() const { return time_; }
  long steps() const { return steps_; }
  double dt() const { return dt_; }
  const SolverParams& params() const { return prm_; }
  const ParticleSet<D>& particles() const { return ps_; }
  const CellGrid<D>& grid() const { return grid_; }
  const ExclusionCounts& excluded() const { return excluded_; }
  const PhaseTimes& phase_times() const { return times_; }
  std::size_t fluid_count() const;

  // Pressure of every active particle in the current order (recomputed from density).
  const std::vector<double>& pressure();

  // Restores a saved state (restart): time, step count and the Verlet phase.
  void set_clock(double time, long steps) {
    time_ = time;
    steps_ = steps;
  }

 private:
  void evaluate();  // sort + pressure + pair loop at the current positions
  double choose_dt() const;
  void step_symplectic();
  void step_verlet();
  void sort_particles();
  void finish_density(std::size_t i);

  SolverParams prm_;
  TaitEos eos_;
  ParticleSet<D> ps_;
  CellGrid<D> grid_;
  ForceBuffers<D> f_;
  double time_ = 0.0, dt_ = 0.0, first_dt_ = 0.0;
  long steps_ = 0;
  int verlet_counter_ = 0;
  ExclusionCounts excluded_;
  PhaseTimes times_;
};

extern template class Simulation<2>;
extern template class Simulation<3>;

}  // namespace swell
