// Fickian particle shifting (Lind et al. 2012, J. Comput. Phys. 231:1499-1523) with the
// velocity-scaled diffusion coefficient of Skillen et al. (2013, Comput. Methods Appl. Mech.
// Engrg. 265:163-173), as an operator on the particle set. For each fluid particle a:
//   grad C_a = sum_b V_b [1 + R (W_ab / W(dp))^n] grad_a W_ab     (all roles b, V_b = m_b/rho_b;
//              the bracket is Lind et al.'s anti-clumping term, R = 0.2, n = 4)
//   div r_a  = -sum_b V_b (x_a - x_b) . grad_a W_ab                 (~ D inside the fluid)
//   dr_a     = -A h |v_a| dt grad C_a                               (Skillen et al.: D = A h |v|
//   dt)
// Particles with div r_a < surface_threshold (DualSPHysics' ShiftTFS defaults: 1.5 in 2D, 2.75
// in 3D) are at the free surface: there only the tangential part of dr_a is kept, the normal
// being the outward direction of the kernel-corrected gradient  n = -L grad C0 / |L grad C0|,
// L = [ -sum_b V_b f_ab (x_a - x_b)(x_a - x_b)^T ]^-1 (Bonet & Lok 1999) and grad C0 the plain
// sum_b V_b grad_a W_ab; the particles within the support of a surface particle lose the normal
// part too (compute_shifting). A surface particle whose L is singular (a splash with too few
// neighbours to define a surface) is not shifted. Hydrodynamic values are not corrected for
// the displacement (as DualSPHysics; the shift is a small fraction of dp per step).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

struct ShiftingParams {
  double coefficient = 2.0;        // A in dr = -A h |v| dt grad C (DualSPHysics' ShiftCoef -2)
  double surface_threshold = 0.0;  // div r below this: free surface (0: the default for D)
  double tensile_r = 0.2;          // R of the anti-clumping term (Lind et al. 2012)

  static double default_threshold(int dim) { return dim == 2 ? 1.5 : (dim == 3 ? 2.75 : 0.5); }
  double threshold(int dim) const {
    return surface_threshold > 0.0 ? surface_threshold : default_threshold(dim);
  }
};

// What the last shifting pass did (for tests and the run summary).
struct ShiftingStats {
  std::size_t shifted = 0;  // fluid particles displaced
  std::size_t surface = 0;  // of which at the free surface (tangential shift only)
  std::size_t skipped = 0;  // surface particles without a defined surface normal
  double max_shift = 0.0;   // largest |dr| [m]
};

// Per-particle quantities of the shifting law, for one fluid particle (exposed for tests).
template <int D>
struct ShiftingTerms {
  Vec<D> grad_c = Vec<D>::Zero();   // with the anti-clumping term
  Vec<D> grad_c0 = Vec<D>::Zero();  // plain sum V grad W
  Eigen::Matrix<double, D, D> b = Eigen::Matrix<double, D, D>::Zero();  // L^-1
  double div_r = 0.0;
};

// Sums of particle a over the candidates of its cell (grid sorted for nearby positions: a
// pair that came within the support since the sort is missed only beyond 2h - 2|motion|,
// where grad W is nearly zero).
template <int D, class Kernel>
ShiftingTerms<D> shifting_terms(const ParticleSet<D>& ps, const CellGrid<D>& grid,
                                const Kernel& kernel, double w_dp, double tensile_r,
                                std::size_t a) {
  ShiftingTerms<D> t;
  const double s2 = kernel.support() * kernel.support();
  const double inv_wdp = 1.0 / w_dp;
  const Vec<D> xa = ps.pos[a];
  grid.for_each_candidate(a, [&](std::uint32_t b) {
    if (b == a) return;
    const Vec<D> r = xa - ps.pos[b];
    const double r2 = r.squaredNorm();
    if (!(r2 < s2) || r2 == 0.0) return;
    const double dist = std::sqrt(r2);
    const double f = kernel.f(dist);  // (1/r) dW/dr
    const double V = ps.mass[b] / ps.rho[b];
    const double q = kernel.w(dist) * inv_wdp;
    const double q2 = q * q;
    const Vec<D> g = (V * f) * r;  // V_b grad_a W_ab
    t.grad_c0 += g;
    t.grad_c += (1.0 + tensile_r * q2 * q2) * g;
    t.div_r -= V * f * r2;
    t.b -= (V * f) * r * r.transpose();
  });
  return t;
}

// The displacement of fluid particle a for its terms; sets surface/skipped.
template <int D>
Vec<D> shifting_displacement(const ShiftingTerms<D>& t, double diffusion, double threshold,
                             bool& surface, bool& skipped, Vec<D>* normal = nullptr) {
  Vec<D> dr = -diffusion * t.grad_c;
  surface = t.div_r < threshold;
  skipped = false;
  if (!surface) return dr;
  const double det = t.b.determinant();
  // L^-1 of a particle with neighbours on one side only is still invertible; a nearly
  // singular one (a line of particles, a lone droplet) defines no surface.
  const double scale = t.b.trace() / D;
  if (!(scale > 0.0) || !(std::abs(det) > 1e-6 * std::pow(scale, D))) {
    skipped = true;
    return Vec<D>::Zero();
  }
  const Vec<D> m = t.b.inverse() * t.grad_c0;
  const double len = m.norm();
  if (!(len > 0.0)) return dr;  // symmetric neighbourhood: no preferred normal
  const Vec<D> n = -m / len;
  if (normal) *normal = n;
  dr -= dr.dot(n) * n;
  return dr;
}

// Computes every fluid particle's displacement into `shift` (sized to ps.size(); walls get 0)
// for a step dt, without moving anything. Two passes: the first finds the free-surface
// particles and their normals (`normal`, zero elsewhere); the second removes the normal part
// from the shift of every particle within the kernel support of a surface particle too (the
// free-surface region of Lind et al. 2012), along the kernel-weighted mean of those surface
// normals, so the rows just under the surface are not pushed out through it either.
// Parallel; no allocation once `shift` and `normal` have their size.
template <int D, class Kernel>
ShiftingStats compute_shifting(const ParticleSet<D>& ps, const CellGrid<D>& grid,
                               const Kernel& kernel, const ShiftingParams& sp, double dp, double dt,
                               std::vector<Vec<D>>& shift, std::vector<Vec<D>>& normal) {
  const long n = static_cast<long>(ps.size());
  if (shift.size() < ps.size()) shift.resize(ps.size());
  if (normal.size() < ps.size()) normal.resize(ps.size());
  const double w_dp = kernel.w(dp);
  const double threshold = sp.threshold(D);
  const double ah_dt = sp.coefficient * kernel.h * dt;
  std::size_t surface = 0, skipped = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : surface, skipped)
  for (long i = 0; i < n; ++i) {
    const auto a = static_cast<std::size_t>(i);
    normal[a].setZero();
    if (ps.role[a] != Role::Fluid) {
      shift[a].setZero();
      continue;
    }
    const ShiftingTerms<D> t = shifting_terms<D>(ps, grid, kernel, w_dp, sp.tensile_r, a);
    bool at_surface = false, skip = false;
    shift[a] = shifting_displacement<D>(t, ah_dt * ps.vel[a].norm(), threshold, at_surface, skip,
                                        &normal[a]);
    surface += at_surface;
    skipped += skip;
  }
  std::size_t shifted = 0;
  double max2 = 0.0;
  const double s2 = kernel.support() * kernel.support();
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : shifted) reduction(max : max2)
  for (long i = 0; i < n; ++i) {
    const auto a = static_cast<std::size_t>(i);
    if (ps.role[a] != Role::Fluid) continue;
    if (normal[a].squaredNorm() == 0.0 && shift[a].squaredNorm() > 0.0) {
      Vec<D> m = Vec<D>::Zero();
      grid.for_each_candidate(a, [&](std::uint32_t b) {
        if (normal[b].squaredNorm() == 0.0) return;
        const double r2 = (ps.pos[a] - ps.pos[b]).squaredNorm();
        if (r2 < s2) m += kernel.w(std::sqrt(r2)) * normal[b];
      });
      const double len = m.norm();
      if (len > 0.0) {
        const Vec<D> u = m / len;
        shift[a] -= shift[a].dot(u) * u;
      }
    }
    const double d2 = shift[a].squaredNorm();
    shifted += d2 > 0.0;
    max2 = std::max(max2, d2);
  }
  return {shifted, surface, skipped, std::sqrt(max2)};
}

}  // namespace swell
