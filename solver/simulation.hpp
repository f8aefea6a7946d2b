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

// Everything besides the particles that a restart needs to continue a run bit for bit.
struct SimulationClock {
  double time = 0.0;
  long steps = 0;
  double dt = 0.0;
  double first_dt = 0.0;
  int verlet_counter = 0;
  ExclusionCounts excluded;
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

  // Force per unit mass exerted by the fluid on each active wall particle (fluid particles:
  // their acceleration) at the last evaluation. Valid between steps.
  const std::vector<Vec<D>>& acceleration() const { return f_.ace; }

  // Clock and counters for checkpoints; restore() continues a run from them. The particles
  // must be given to the constructor in the order they were saved.
  SimulationClock clock() const {
    return {time_, steps_, dt_, first_dt_, verlet_counter_, excluded_};
  }
  void restore(const SimulationClock& c) {
    time_ = c.time;
    steps_ = c.steps;
    dt_ = c.dt;
    first_dt_ = c.first_dt;
    verlet_counter_ = c.verlet_counter;
    // Particles excluded by the constructor's sort were still active when saved.
    excluded_.out_of_domain += c.excluded.out_of_domain;
    excluded_.non_finite += c.excluded.non_finite;
    excluded_.density_out_of_range += c.excluded.density_out_of_range;
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
