#include "bc/mdbc.hpp"

#include <algorithm>
#include <stdexcept>

#include "solver/physics/kernels.hpp"
#include "solver/physics/wcsph_forces.hpp"

namespace swell {

template <int D>
void MdbcBoundary<D>::before_forces(StepState<D>& s) {
  ParticleSet<D>& ps = s.particles;
  if (ps.normal.size() != ps.stored())
    throw std::invalid_argument(
        "mDBC: the particles carry no wall normals (from a checkpoint written by a run with DBC "
        "walls? restart with the case the run was started with)");
  const long n = static_cast<long>(ps.size());
  const bool slip = slip_ != MdbcSlip::Wall;
  if (slip && body_vel_.size() < ps.total()) body_vel_.resize(ps.total());  // once
  const double rho0 = s.params.rho0;
  const CellGrid<D>& grid = s.grid;
  const bool hydrostatic = pressure_ == MdbcPressure::Hydrostatic;
  const Vec<D> gravity = s.params.gravity.template head<D>();
  const bool accelerating = !ps.wall_acc.empty();
  const TaitEos& eos = s.eos;
  // rho_a = p^-1(p(rho_g) + rho0 (g - a_a) . (x_a - x_g)), x_a - x_g = -2 n_a (at least rho0)
  const auto cloned = [&](long i, double rho_g) {
    Vec<D> f = gravity;
    if (accelerating && ps.role[i] == Role::MovingWall) f -= ps.wall_acc[i];
    const double p = eos.pressure(rho_g) - 2.0 * rho0 * f.dot(ps.normal[i]);
    return p > 0.0 ? eos.density(p) : rho0;
  };
  std::size_t corrected = 0, shepard = 0, dry = 0;
  with_kernel<D>(s.params.kernel, s.params.h, [&](const auto& kernel) {
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : corrected, shepard, dry)
    for (long i = 0; i < n; ++i) {
      if (is_fluid(ps.role[i]) || dbc_wall(ps, static_cast<std::size_t>(i))) continue;
      const Vec<D> xg = ps.pos[i] + 2.0 * ps.normal[i];
      GhostValue<D> g;
      if (grid.inside_domain(xg) && grid.fluid_near(grid.cell_index(xg)))
        g = ghost_interpolate<D>(ps, grid, kernel, xg, det_min_, slip);
      if (slip) body_vel_[i] = ps.vel[i];
      switch (g.mode) {
        case GhostMode::Dry:
          ps.rho[i] = static_cast<StateReal>(rho0);
          ++dry;
          continue;  // the wall shows its body's velocity
        case GhostMode::Shepard:
          ps.rho[i] =
              static_cast<StateReal>(hydrostatic ? cloned(i, g.rho) : std::max(rho0, g.rho));
          ++shepard;
          break;
        case GhostMode::Corrected:
          // linear: rho_a = rho_g + (x_a - x_g) . grad rho_g, x_a - x_g = -2 n_a
          ps.rho[i] = static_cast<StateReal>(
              hydrostatic ? cloned(i, g.rho)
                          : std::max(rho0, g.rho - 2.0 * ps.normal[i].dot(g.grad)));
          ++corrected;
          break;
      }
      if (!slip) continue;
      const Vec<D> vb = widen<D>(ps.vel[i]);
      if (slip_ == MdbcSlip::NoSlip) {
        ps.vel[i] = narrow<D>(2.0 * vb - g.vel);
      } else {  // free slip: tangential part of the ghost's, normal part mirrored
        const double len = ps.normal[i].norm();
        if (len > 0.0) {
          const Vec<D> u = ps.normal[i] / len;
          ps.vel[i] = narrow<D>(g.vel + 2.0 * (vb - g.vel).dot(u) * u);
        }
      }
    }
    return 0;
  });
  counts_ = {corrected, shepard, dry};
}

template <int D>
void MdbcBoundary<D>::forces(StepState<D>& s) {
  compute_forces<D, Selection>(s.particles, s.grid, s.params, s.eos, s.forces);
}

template <int D>
void MdbcBoundary<D>::after_forces(StepState<D>& s) {
  ParticleSet<D>& ps = s.particles;
  const std::size_t n = ps.size();
  const bool slip = slip_ != MdbcSlip::Wall;
  for (std::size_t i = 0; i < n; ++i) {
    if (is_fluid(ps.role[i]) || dbc_wall(ps, i)) continue;
    s.forces.drho[i] = 0.0;
    if (slip) ps.vel[i] = body_vel_[i];
  }
}

template <int D>
void MdbcBoundary<D>::finish_density(StepState<D>& s) {
  if (dbc_bodies_.empty()) return;
  ParticleSet<D>& ps = s.particles;
  const double rho0 = s.params.rho0;
  const std::size_t n = ps.size();
  for (std::size_t i = 0; i < n; ++i)
    if (is_wall(ps.role[i]) && dbc_wall(ps, i) && ps.rho[i] < rho0) ps.rho[i] = rho0;
}

template class MdbcBoundary<2>;
template class MdbcBoundary<3>;

}  // namespace swell
