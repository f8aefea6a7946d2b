// The time loop of one WCSPH run: neighbour sort, forces (the boundary model), time step,
// integration by role, and the step hooks around them (step_hooks.hpp).
//
// Simulation owns the particles, the boundary model, the hooks and every buffer the loop
// needs; after construction a step allocates nothing. Output and gauges read particles()
// between steps.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/physics/eos.hpp"
#include "solver/physics/wcsph_forces.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/time/clock.hpp"
#include "solver/time/exchange.hpp"
#include "solver/time/step_hooks.hpp"

namespace swell {

template <int D>
class Simulation {
 public:
  using Hooks = std::vector<std::unique_ptr<StepHook<D>>>;

  // `boundary` runs the force stage (bc/dbc.hpp: make_dbc); `hooks` run at their stages in
  // the order given. Particles of moving walls must be placed at their t = 0 pose by the caller
  // (bc/motion's MovingBodies::place_initial) or come from a checkpoint.
  // `exchange` (a run on several ranks, parallel/halo.hpp): `particles` are this rank's share;
  // without one the run is a single rank, as always.
  Simulation(const SolverParams& params, ParticleSet<D> particles,
             std::unique_ptr<BoundaryModel<D>> boundary, Hooks hooks = {},
             std::unique_ptr<Exchange<D>> exchange = nullptr);

  // Advances by one (variable) time step.
  void step();

  double time() const { return time_; }
  long steps() const { return steps_; }
  double dt() const { return dt_; }
  const SolverParams& params() const { return prm_; }
  const ParticleSet<D>& particles() const { return ps_; }
  const CellGrid<D>& grid() const { return grid_; }
  const ExclusionCounts& excluded() const { return excluded_; }
  // Particles that left the domain, per face, with times (restored by restore_faces()).
  const FaceExclusions& excluded_faces() const { return faces_; }
  void restore_faces(const FaceExclusions& f) { faces_ = f; }
  // The fluid particle excluded for its density farthest from rho0 (the largest of
  // rho/rho0 and rho0/rho), for the watchdog; ratio 0 while none was.
  struct DensityExclusion {
    double ratio = 0.0, rho = 0.0, time = 0.0;
    std::uint32_t id = 0;
    Vec<D> pos = Vec<D>::Zero();
  };
  const DensityExclusion& worst_density_exclusion() const { return worst_rho_; }
  const PhaseTimes& phase_times() const { return times_; }
  // The decomposition of a run on several ranks (null on one rank).
  const Exchange<D>* exchange() const { return exchange_.get(); }
  // Several ranks, between steps: sends the particles that left this rank's part to their
  // owners now (no rebalance). acceleration() and density_rate() are stale afterwards.
  // Collective; nothing on one rank.
  void redistribute();
  std::size_t fluid_count() const;

  // Pressure of every particle (active, then excluded) in the current order, recomputed from
  // density. Valid until the next step (the array is a force buffer the step reuses).
  const std::vector<double>& pressure();

  // Force per unit mass exerted by the fluid on each active wall particle (fluid particles:
  // their acceleration) at the last evaluation. Valid between steps.
  const std::vector<Vec<D>>& acceleration() const { return f_.ace; }
  // drho/dt of each active particle at the last evaluation, as the integrator used it (mDBC
  // walls: 0). Valid between steps.
  const std::vector<double>& density_rate() const { return f_.drho; }

  // Clock and counters for checkpoints; restore() continues a run from them. The particles
  // must be given to the constructor in the order they were saved.
  SimulationClock clock() const {
    return {time_, steps_, dt_, first_dt_, verlet_counter_, excluded_};
  }
  void restore(const SimulationClock& c);

  // The boundary model's and the hooks' checkpoint state, as "hook.<name>.<key>" entries.
  void save_hooks(std::map<std::string, double>& out) const;
  void restore_hooks(const std::map<std::string, double>& in);

 private:
  StepState<D> state(double t) { return {ps_, grid_, f_, prm_, eos_, t, dt_, exchange_.get()}; }
  void evaluate();  // sort + before_forces + forces + after_forces at the current positions
  double choose_dt() const;  // the global minimum on several ranks
  double local_dt() const;
  void step_symplectic();
  void step_verlet();
  // between_steps: the sort after the integration (density exclusions), which keeps the
  // force buffers' values (reordered with the particles) instead of using them as scratch.
  void sort_particles(bool between_steps = false);
  // The force buffers as a reorder's scratch (only where the rates are dead: the sort at the
  // start of an evaluation).
  LentScratch<D> lent_force_buffers();
  // Files the particles the last sort moved out of the domain, [first, last), by face.
  void record_faces(std::size_t first, std::size_t last);
  // prescribe + finish_density at time t, after an integration substep.
  void after_substep(double t);
  // The periodic images' and the remote images' state from their sources (collective on
  // several ranks).
  void refresh_images();
  template <class Stage>
  void for_each_hook(Stage&& stage);
  // Whether test(hook) holds for the boundary model or some hook (the same on every rank: the
  // hooks come from the case file).
  template <class Test>
  bool any_hook(Test&& test) const;

  SolverParams prm_;
  TaitEos eos_;
  ParticleSet<D> ps_;
  std::unique_ptr<BoundaryModel<D>> boundary_;
  Hooks hooks_;
  std::unique_ptr<Exchange<D>> exchange_;
  CellGrid<D> grid_;
  ForceBuffers<D> f_;
  double time_ = 0.0, dt_ = 0.0, first_dt_ = 0.0;
  long steps_ = 0;
  int verlet_counter_ = 0;
  ExclusionCounts excluded_;
  FaceExclusions faces_;
  DensityExclusion worst_rho_;
  PhaseTimes times_;
};

extern template class Simulation<2>;
extern template class Simulation<3>;

}  // namespace swell
