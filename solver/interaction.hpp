// The particle-pair loop, written once (STYLE.md): for every active particle a, gather the
// contributions of its neighbours b into drho_a/dt and dv_a/dt. Parallel over cells with
// OpenMP; each thread writes only the particles of its own cells, so there are no atomics.
//
// Equations (DESIGN.md, defaults as DualSPHysics):
//   drho_a/dt = sum_b m_b v_ab . gradW_ab + density diffusion (fluid-fluid pairs)
//   dv_a/dt   = -sum_b m_b (P_a/rho_a^2 + P_b/rho_b^2 + Pi_ab) gradW_ab + viscous + g
// Boundary (DBC) particles get drho/dt from their fluid neighbours only; their `ace` holds the
// force per unit mass exerted on them by the fluid (for force gauges) and is never integrated.
#pragma once

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "solver/cell_grid.hpp"
#include "solver/particle_set.hpp"
#include "solver/physics_terms.hpp"
#include "solver/solver_params.hpp"

namespace swell {

template <int D>
struct ForceBuffers {
  std::vector<Vec<D>> ace;
  std::vector<double> drho;
  std::vector<double> press;  // P_a
  std::vector<double> prs;    // P_a / rho_a^2
  std::vector<double> cs;     // c_a
  double visc_dt_max = 0.0;   // max over pairs of h |v_ab.r_ab| / (r^2 + eta^2), for dt
  double cs_max = 0.0;

  void resize(std::size_t n) {
    ace.resize(n);
    drho.resize(n);
    press.resize(n);
    prs.resize(n);
    cs.resize(n);
  }
};

// Pressure, P/rho^2 and sound speed of every active particle.
template <int D>
void compute_pressure(const ParticleSet<D>& ps, const TaitEos& eos, ForceBuffers<D>& out) {
  const long n = static_cast<long>(ps.size());
  double cs_max = 0.0;
#pragma omp parallel for schedule(static) reduction(max : cs_max)
  for (long i = 0; i < n; ++i) {
    const double rho = ps.rho[i];
    const double p = eos.pressure(rho);
    out.press[i] = p;
    out.prs[i] = p / (rho * rho);
    out.cs[i] = eos.sound_speed(rho);
    cs_max = std::max(cs_max, out.cs[i]);
  }
  out.cs_max = cs_max;
}

template <int D, class Kernel, ViscosityModel VM>
void interact(const ParticleSet<D>& ps, const CellGrid<D>& grid, const Kernel& kernel,
              const SolverParams& prm, ForceBuffers<D>& out) {
  using V = Vec<D>;
  const double support2 = kernel.support() * kernel.support();
  const double h = prm.h, eta2 = prm.eta2();
  const V g = prm.gravity.template head<D>();
  const ArtificialViscosity av{prm.alpha, h, eta2};
  const LaminarViscosity lam{prm.nu, eta2};
  const bool diffuse = prm.diffusion != DiffusionModel::None;
  const DensityDiffusion dd{
      diffuse ? prm.delta * h * prm.c0 : 0.0,
      prm.diffusion == DiffusionModel::Fourtakas ? prm.rho0 / (prm.c0 * prm.c0) : 0.0};
  const long ncells = static_cast<long>(grid.num_cells());
  double visc_dt_max = 0.0;

#pragma omp parallel for schedule(dynamic, 16) reduction(max : visc_dt_max)
  for (long c = 0; c < ncells; ++c) {
    const std::uint32_t cb = grid.begin(c), ce = grid.end(c);
    if (cb == ce) continue;
    if (!grid.fluid_near(c)) {  // dry wall cell: nothing to gather
      for (std::uint32_t a = cb; a < ce; ++a) {
        out.drho[a] = 0.0;
        out.ace[a] = V::Zero();
      }
      continue;
    }
    std::array<std::pair<std::uint32_t, std::uint32_t>, (D == 3 ? 9 : 3)> ranges;
    int nr = 0;
    grid.for_each_neighbour_range(c, [&](std::uint32_t b, std::uint32_t e) {
      ranges[nr++] = {b, e};
    });

    for (std::uint32_t a = cb; a < ce; ++a) {
      const V xa = ps.pos[a], va = ps.vel[a];
      const double rho_a = ps.rho[a], prs_a = out.prs[a], cs_a = out.cs[a];
      const bool fluid_a = ps.kind[a] == Kind::Fluid;
      double drho = 0.0;
      V acc = V::Zero();
      for (int r = 0; r < nr; ++r) {
        for (std::uint32_t b = ranges[r].first; b < ranges[r].second; ++b) {
          const V rab = xa - ps.pos[b];
          const double r2 = rab.squaredNorm();
          if (r2 >= support2 || r2 < 1e-18) continue;
          const bool fluid_b = ps.kind[b] == Kind::Fluid;
          if (!fluid_a && !fluid_b) continue;  // wall-wall pairs do nothing under DBC
          const double fr = kernel.f(std::sqrt(r2));
          const V gradw = rab * fr;
          const V vab = va - ps.vel[b];
          const double m_b = ps.mass[b];
          drho += m_b * vab.dot(gradw);

          // Pressure and viscous force. For a wall particle this is the force per unit mass
          // the fluid exerts on it (used by force gauges), not integrated.
          const double rho_b = ps.rho[b];
          const double vr = vab.dot(rab);
          double pterm = prs_a + out.prs[b];
          if constexpr (VM == ViscosityModel::Artificial) {
            pterm += av.pi(vr, r2, 0.5 * (cs_a + out.cs[b]), 0.5 * (rho_a + rho_b));
          } else {
            acc += (m_b * lam.factor(r2 * fr, r2, rho_a, rho_b)) * vab;
          }
          acc -= (m_b * pterm) * gradw;
          if (!fluid_a) continue;

          if (vr < 0.0) visc_dt_max = std::max(visc_dt_max, -h * vr / (r2 + eta2));
          if (diffuse && fluid_b)
            drho += dd.drho(rho_a, rho_b, -g.dot(rab), r2 * fr, r2, eta2, m_b / rho_b);
        }
      }
      out.drho[a] = drho;
      out.ace[a] = fluid_a ? V(acc + g) : acc;
    }
  }
  out.visc_dt_max = visc_dt_max;
}

}  // namespace swell
