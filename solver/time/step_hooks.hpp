// Step stages and the hooks that plug into them (bc/ modules: dbc, motion; later mdbc, damping,
// floating bodies). A step runs, in this order:
//   evaluate: sort -> before_forces -> forces (the boundary model) -> after_forces
//   integrate (by role) -> prescribe (moving walls at the substep time) -> finish_density
//   ... (the symplectic corrector evaluates and integrates once more) ...
//   after_integration
// and save/restore carry a hook's state through checkpoints. Each hook is called once per stage
// (a virtual call per stage, never one per particle or pair).
#pragma once

#include <map>
#include <string>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/physics/eos.hpp"
#include "solver/physics/wcsph_forces.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/time/exchange.hpp"

namespace swell {

// What a hook may read or change at a stage.
template <int D>
struct StepState {
  ParticleSet<D>& particles;
  const CellGrid<D>& grid;  // sorted for the current positions in the force stages
  // Rates of the last evaluation, from after_forces on. In before_forces they hold nothing
  // meaningful: the sort used them as its reorder scratch (ParticleSet::permute).
  ForceBuffers<D>& forces;
  const SolverParams& params;
  const TaitEos& eos;
  double time;  // the time the particles are at (the substep time in prescribe)
  double dt;    // the step being taken (0 before the first)
  // The decomposition of a run on several ranks (null on one): for a hook that must exchange
  // values it computes for the halo images.
  Exchange<D>* exchange = nullptr;
};

template <int D>
class StepHook {
 public:
  virtual ~StepHook() = default;
  // Short lower-case name, used as the prefix of the hook's checkpoint entries.
  virtual std::string name() const = 0;
  virtual void prescribe(StepState<D>&) {}
  virtual void before_forces(StepState<D>&) {}
  virtual void after_forces(StepState<D>&) {}
  virtual void finish_density(StepState<D>&) {}
  virtual void after_integration(StepState<D>&) {}
  // Whether the images (periodic, and the halo of a run on several ranks) must take their
  // sources' state again after this hook's before_forces (it changes pos, vel or rho there),
  // and whether its after_integration reads images. The Simulation refreshes the images at those
  // two points only where some hook says so (a collective exchange on several ranks). The
  // defaults are the safe answers; a hook that neither changes nor reads says so.
  virtual bool changes_state_before_forces() const { return true; }
  virtual bool reads_images_after_integration() const { return true; }
  // Checkpoint state as named numbers (keys without the "hook.<name>." prefix).
  virtual void save(std::map<std::string, double>&) const {}
  virtual void restore(const std::map<std::string, double>&) {}
};

// The boundary model: a hook that also owns the force stage, i.e. runs the pair loop with its
// own selection policy (which b a particle a may see). DBC is bc/dbc.hpp.
template <int D>
class BoundaryModel : public StepHook<D> {
 public:
  virtual void forces(StepState<D>&) = 0;
};

}  // namespace swell
