// Dynamic boundary conditions (Crespo et al. 2007) as a boundary module: wall particles carry
// density and pressure from the continuity equation and EoS like fluid, but take their
// positions from their role (fixed, or prescribed by bc/motion). The module owns
//   - the wall selection of the pair loop (WallsSeeFluid: walls see fluid only, continuity
//     only, dry cells skipped),
//   - the density floor: a wall particle's density never drops below rho0, so walls never pull
//     fluid in (the finish_density stage),
//   - the hydrostatic initial densities of fluid and wetted walls (initialise_hydrostatic).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/neighbours/gather.hpp"
#include "solver/physics/eos.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/time/step_hooks.hpp"

namespace swell {

template <int D>
class DbcBoundary final : public BoundaryModel<D> {
 public:
  using Selection = WallsSeeFluid;
  std::string name() const override { return "dbc"; }
  bool changes_state_before_forces() const override { return false; }
  bool reads_images_after_integration() const override { return false; }
  // The pair loop with DBC's wall selection (defined in bc/dbc.cpp, where the loop is compiled).
  void forces(StepState<D>& s) override;
  // Parallel like the integration before it, each thread on its own particles: a serial pass
  // would first pull the other threads' densities into one core's cache.
  void finish_density(StepState<D>& s) override {
    ParticleSet<D>& ps = s.particles;
    const double rho0 = s.params.rho0;
    const long n = static_cast<long>(ps.size());
#pragma omp parallel for schedule(static) if (n > ParticleSet <D>::kParallelMin)
    for (long i = 0; i < n; ++i)
      if (is_wall(ps.role[i]) && ps.rho[i] < rho0) ps.rho[i] = rho0;
  }
};

template <int D>
std::unique_ptr<BoundaryModel<D>> make_dbc() {
  return std::make_unique<DbcBoundary<D>>();
}

extern template class DbcBoundary<2>;
extern template class DbcBoundary<3>;

// Free-surface level of each fluid body along "up" (-g): the top particle plus dp/2.
template <int D>
std::map<std::uint16_t, double> fluid_levels(const ParticleSet<D>& ps, const Vec<D>& up,
                                             double dp) {
  std::map<std::uint16_t, double> level;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.role[i] != Role::Fluid) continue;
    const double z = ps.pos[i].dot(up) + 0.5 * dp;
    auto [it, fresh] = level.emplace(ps.body[i], z);
    if (!fresh) it->second = std::max(it->second, z);
  }
  return level;
}

// What initialise_hydrostatic takes from the whole case when `ps` is one share of it (a set-up
// distributed over ranks, case/setup.cpp): the fluid bodies' levels and the box of every
// particle (the sort's grid), so each share sorts and reads as the whole set would.
template <int D>
struct HydrostaticFrame {
  std::map<std::uint16_t, double> level;
  Vec<D> lo, hi;
};

// Hydrostatic initial density, so a tank at rest starts at rest: a fluid particle at depth d
// below its body's free surface gets rho = rho0 (1 + rho0 g d / B)^(1/gamma). A wall particle
// within the kernel support of fluid gets the density of that depth too (else the first steps
// would compress the fluid against walls at rho0); other wall particles get rho0.
// Reorders the particles (cell sort; stable, over the particles' box padded by one support);
// ids are kept. `frame`: the whole case's levels and box (default: those of `ps`).
template <int D>
void initialise_hydrostatic(ParticleSet<D>& ps, const SolverParams& prm,
                            const HydrostaticFrame<D>* frame = nullptr) {
  const TaitEos eos(prm.rho0, prm.c0, prm.gamma);
  const Vec<D> g = prm.gravity.template head<D>();
  const double gnorm = g.norm();
  for (std::size_t i = 0; i < ps.size(); ++i) ps.rho[i] = prm.rho0;
  if (gnorm > 0.0) {
    const Vec<D> up = -g / gnorm;
    const auto level = frame ? frame->level : fluid_levels(ps, up, prm.dp);
    const double support = kernel_support_factor(prm.kernel) * prm.h;
    Vec<D> lo = frame ? frame->lo : ps.pos[0], hi = frame ? frame->hi : ps.pos[0];
    for (std::size_t i = 0; i < ps.size() && !frame; ++i) {
      lo = lo.cwiseMin(ps.pos[i]);
      hi = hi.cwiseMax(ps.pos[i]);
    }
    CellGrid<D> grid(lo.array() - support, hi.array() + support, support);
    // In place: a set-up sort needs no reorder scratch (the set-up's memory peak).
    typename CellGrid<D>::Reorder in_place;
    in_place.in_place = true;
    grid.sort(ps, in_place);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      double top = -std::numeric_limits<double>::infinity();
      if (ps.role[i] == Role::Fluid) {
        top = level.at(ps.body[i]);
      } else {
        grid.for_each_candidate(i, [&](std::uint32_t j) {
          if (ps.role[j] == Role::Fluid && (ps.pos[j] - ps.pos[i]).norm() < support)
            top = std::max(top, level.at(ps.body[j]));
        });
      }
      const double depth = top - ps.pos[i].dot(up);
      if (depth > 0.0) ps.rho[i] = eos.hydrostatic_density(gnorm * depth);
    }
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    ps.rho_prev[i] = ps.rho[i];
    ps.vel_prev[i] = ps.vel[i];
  }
}

}  // namespace swell
