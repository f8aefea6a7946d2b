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
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/neighbours/gather.hpp"
#include "solver/neighbours/pair_driver.hpp"
#include "solver/physics/corrections.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

struct ShiftingParams {
  double coefficient = 2.0;        // A in dr = -A h |v| dt grad C (DualSPHysics' ShiftCoef -2)
  double surface_threshold = 0.0;  // div r below this: free surface (0: the default for D)
  double tensile_r = 0.2;          // R of the anti-clumping term (Lind et al. 2012)
  // Move each shifted particle's density with it: rho_a += dr_a . grad rho_a (the first-order
  // Taylor correction of Lind et al. 2012, section 3.3), grad rho in the kernel-gradient-
  // corrected difference form over the fluid neighbours (Bonet & Lok 1999; no correction where
  // the moment matrix is near singular, |det| < 0.1).
  bool correct_density = false;
  ShiftMode mode = ShiftMode::Full;

  static double default_threshold(int dim) { return dim == 2 ? 1.5 : (dim == 3 ? 2.75 : 0.5); }
  double threshold(int dim) const {
    return surface_threshold > 0.0 ? surface_threshold : default_threshold(dim);
  }
};

// What the last shifting pass did (for tests and the run summary).
struct ShiftingStats {
  std::size_t shifted = 0;    // fluid particles displaced
  std::size_t surface = 0;    // of which at the free surface (tangential shift only)
  std::size_t skipped = 0;    // surface particles without a defined surface normal
  std::size_t near_wall = 0;  // fluid particles left unshifted by the mode (nobound, nofixed)
  double max_shift = 0.0;     // largest |dr| [m]
};

// Per-particle quantities of the shifting law, for one fluid particle (exposed for tests).
template <int D>
struct ShiftingTerms {
  Vec<D> grad_c = Vec<D>::Zero();   // with the anti-clumping term
  Vec<D> grad_c0 = Vec<D>::Zero();  // plain sum V grad W
  Eigen::Matrix<double, D, D> b = Eigen::Matrix<double, D, D>::Zero();  // L^-1
  double div_r = 0.0;
};

// Buffers of compute_shifting, sized once and reused (no allocation in the time loop).
template <int D>
struct ShiftingWork {
  std::vector<Vec<D>> shift;            // the displacement of each particle (0 for walls)
  std::vector<Vec<D>> normal;           // outward surface normal (0 off the surface)
  std::vector<double> vol;              // m / rho of each particle
  std::vector<std::uint8_t> cell_flag;  // cells holding a surface particle
  std::vector<Vec<D>> grad_c;           // grad C of each particle (pass 1)
  std::vector<double> div_r;            // div r of each particle (pass 1)
  std::vector<std::uint8_t> near_wall;  // a wall the mode excludes within the support (pass 1)
  std::vector<double> drho;             // density correction of each particle (correct_density)
  NeighbourLists lists;                 // the pair driver's per-thread lists
};

// Pass 1 as an evaluator of the pair driver (neighbours/pair_driver.hpp), so it runs in the
// same SIMD loop as the forces: s0..s(D-1) sum grad C with the anti-clumping term, s3 sums
// div r. A padding entry (b == a, r = 0) adds exactly zero. Plain arithmetic, no intrinsics.
// kWalls: also flag a wall neighbour the mode excludes (in the max slot); without it (mode
// full) the loop is the one before the modes existed, so full-mode runs stay bitwise.
template <int D, class Kernel, bool kWalls = false>
class ShiftingEvaluator {
 public:
  using Real = double;
  struct Centre {
    double x0, x1, x2;
  };
  ShiftingEvaluator(const ParticleSet<D>& ps, const Kernel& kernel, const double* vol,
                    double inv_wdp, double tensile_r, Vec<D>* grad_c, double* div_r,
                    ShiftMode mode = ShiftMode::Full, std::uint8_t* near_wall = nullptr)
      : kernel_(kernel),
        P_(ps.pos.data()->data()),
        role_(ps.role.data()),
        vol_(vol),
        inv_wdp_(inv_wdp),
        tensile_r_(tensile_r),
        grad_c_(grad_c),
        div_r_(div_r),
        mode_(mode),
        near_wall_(near_wall) {}

  Centre centre(std::uint32_t a, bool) const {
    return {P_[a * D], P_[a * D + 1], D == 3 ? P_[a * D + D - 1] : 0.0};
  }
  void pair(const Centre& a, std::uint32_t e, double& g0, double& g1, double& g2, double& div,
            double& wall) const {
    const std::uint32_t b = e & ~kWallBit;
    // A wall neighbour the mode excludes (the list holds only neighbours within the support).
    if constexpr (kWalls) {
      if ((e & kWallBit) && (mode_ == ShiftMode::NoBound || role_[b] == Role::FixedWall))
        wall = 1.0;
    } else {
      (void)wall;
    }
    const double r0 = a.x0 - P_[b * D], r1 = a.x1 - P_[b * D + 1];
    const double r2c = D == 3 ? a.x2 - P_[b * D + D - 1] : 0.0;
    const double r2 = r0 * r0 + r1 * r1 + r2c * r2c;
    const double r = std::sqrt(std::max(r2, 1e-18));
    const double vf = vol_[b] * kernel_.fs(r);  // V_b (1/r) dW/dr
    const double q = kernel_.w(r) * inv_wdp_;
    const double q2 = q * q;
    const double t = vf * (1.0 + tensile_r_ * q2 * q2);
    g0 += t * r0;
    g1 += t * r1;
    g2 += t * r2c;
    div -= vf * r2;
  }
  double finish(std::uint32_t a, const Centre&, double g0, double g1, double g2, double div,
                double wall) {
    const double g[3] = {g0, g1, g2};
    for (int d = 0; d < D; ++d) grad_c_[a][d] = g[d];
    div_r_[a] = div;
    if (near_wall_) near_wall_[a] = wall > 0.0 ? 1 : 0;
    return 0.0;
  }
  void idle(std::uint32_t a) {
    grad_c_[a].setZero();
    div_r_[a] = 0.0;
    if (near_wall_) near_wall_[a] = 0;
  }

 private:
  Kernel kernel_;
  const double* P_;
  const Role* role_;
  const double* vol_;
  double inv_wdp_, tensile_r_;
  Vec<D>* grad_c_;
  double* div_r_;
  ShiftMode mode_;
  std::uint8_t* near_wall_;
};

// Calls fn(b, r, r2, dist) for every particle b != a within the support of particle a (grid
// sorted for nearby positions: a pair that came within the support since the sort is missed
// only beyond 2h - 2|motion|, where grad W is nearly zero).
template <int D, class Kernel, class Fn>
void for_each_shifting_pair(const ParticleSet<D>& ps, const CellGrid<D>& grid, const Kernel& kernel,
                            std::size_t a, Fn&& fn) {
  const double s2 = kernel.support() * kernel.support();
  const Vec<D> xa = ps.pos[a];
  grid.for_each_neighbour_range(grid.cell_of(a), [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t b = begin; b < end; ++b) {
      const Vec<D> r = xa - ps.pos[b];
      const double r2 = r.squaredNorm();
      if (!(r2 < s2) || r2 == 0.0) continue;  // also a itself
      fn(b, r, r2, std::sqrt(r2));
    }
  });
}

// grad C, grad C0 and div r of particle a; vol[b] = m_b / rho_b.
template <int D, class Kernel>
void shifting_sums(const ParticleSet<D>& ps, const CellGrid<D>& grid, const Kernel& kernel,
                   const std::vector<double>& vol, double inv_wdp, double tensile_r, std::size_t a,
                   ShiftingTerms<D>& t) {
  for_each_shifting_pair<D>(ps, grid, kernel, a,
                            [&](std::uint32_t b, const Vec<D>& r, double r2, double dist) {
                              const double vf = vol[b] * kernel.f(dist);  // V_b (1/r) dW/dr
                              const double q = kernel.w(dist) * inv_wdp;
                              const double q2 = q * q;
                              const Vec<D> g = vf * r;  // V_b grad_a W_ab
                              t.grad_c0 += g;
                              t.grad_c += (1.0 + tensile_r * q2 * q2) * g;
                              t.div_r -= vf * r2;
                            });
}

// L^-1 of particle a (needed at the free surface only).
template <int D, class Kernel>
void shifting_matrix(const ParticleSet<D>& ps, const CellGrid<D>& grid, const Kernel& kernel,
                     const std::vector<double>& vol, std::size_t a, ShiftingTerms<D>& t) {
  for_each_shifting_pair<D>(ps, grid, kernel, a,
                            [&](std::uint32_t b, const Vec<D>& r, double, double dist) {
                              t.b -= (vol[b] * kernel.f(dist)) * r * r.transpose();
                            });
}

// Every term of particle a (for tests and diagnostics).
template <int D, class Kernel>
ShiftingTerms<D> shifting_terms(const ParticleSet<D>& ps, const CellGrid<D>& grid,
                                const Kernel& kernel, double w_dp, double tensile_r,
                                std::size_t a) {
  std::vector<double> vol(ps.size());
  for (std::size_t b = 0; b < ps.size(); ++b) vol[b] = ps.mass[b] / ps.rho[b];
  ShiftingTerms<D> t;
  shifting_sums<D>(ps, grid, kernel, vol, 1.0 / w_dp, tensile_r, a, t);
  shifting_matrix<D>(ps, grid, kernel, vol, a, t);
  return t;
}

// The outward normal of a surface particle from its terms: -L grad C0, normalised; zero where
// L^-1 is nearly singular (a line of particles, a lone droplet: no surface defined, `skipped`)
// or grad C0 vanishes (a symmetric neighbourhood).
template <int D>
Vec<D> surface_normal(const ShiftingTerms<D>& t, bool& skipped) {
  skipped = false;
  const double det = t.b.determinant();
  const double scale = t.b.trace() / D;
  if (!(scale > 0.0) || !(std::abs(det) > 1e-6 * std::pow(scale, D))) {
    skipped = true;
    return Vec<D>::Zero();
  }
  const Vec<D> m = t.b.inverse() * t.grad_c0;
  const double len = m.norm();
  return len > 0.0 ? Vec<D>(-m / len) : Vec<D>::Zero();
}

// Computes every fluid particle's displacement into work.shift (walls get 0) for a step dt,
// without moving anything:
//   1. every particle: grad C and div r, in the pair driver's SIMD loop (ShiftingEvaluator);
//   2. the fluid particles at the free surface (div r < threshold): L and grad C0 (a scalar
//      loop over their neighbours), the surface normal, and the shift loses its normal part (a
//      surface particle without a defined normal is not shifted);
//   3. every other fluid particle within the kernel support of a surface particle (the free-
//      surface region of Lind et al. 2012) loses the normal part too, along the kernel-weighted
//      mean of those particles' normals, so the rows just under the surface are not pushed out
//      through it either. Only particles in cells next to a surface particle's cell look.
// A particle at rest has no shift (D = A h |v| dt = 0). Parallel; no allocation once the
// buffers have their size.
// `remote_normals(normal, ghost_begin)`: on several ranks, fills the halo images' normals from
// their owners (collective: every rank calls it); the default does nothing.
struct NoRemoteImages {
  template <class V>
  void operator()(V&, std::size_t) const {}
};
template <int D, class Kernel, class RemoteNormals = NoRemoteImages>
ShiftingStats compute_shifting(const ParticleSet<D>& ps, const CellGrid<D>& grid,
                               const Kernel& kernel, const ShiftingParams& sp, double dp, double dt,
                               ShiftingWork<D>& work,
                               RemoteNormals&& remote_normals = NoRemoteImages{}) {
  const std::size_t np = ps.size();
  const long n = static_cast<long>(np);
  // Neighbours may be periodic images (stored after the particles): vol and normal cover them.
  const std::size_t ns = ps.stored(), gb = ps.ghost_begin();
  if (work.shift.size() < np) work.shift.resize(np);
  if (work.normal.size() < ns) work.normal.resize(ns);
  if (work.vol.size() < ns) work.vol.resize(ns);
  if (work.grad_c.size() < np) work.grad_c.resize(np);
  if (work.div_r.size() < np) work.div_r.resize(np);
  if (work.near_wall.size() < np) work.near_wall.resize(np);
  if (work.cell_flag.size() < grid.num_cells()) work.cell_flag.resize(grid.num_cells());
  std::vector<Vec<D>>& shift = work.shift;
  std::vector<Vec<D>>& normal = work.normal;
  const std::vector<double>& vol = work.vol;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) work.vol[i] = ps.mass[i] / ps.rho[i];
  for (std::size_t i = gb; i < ns; ++i) work.vol[i] = ps.mass[i] / ps.rho[i];
  const double inv_wdp = 1.0 / kernel.w(dp);
  const auto pass1 = [&](auto walls) {  // walls: std::bool_constant, the evaluator's kWalls
    for_each_pair<D, WallsSeeFluid>(
        ps, grid, kernel.support(),
        ShiftingEvaluator<D, Kernel, decltype(walls)::value>(
            ps, kernel, work.vol.data(), inv_wdp, sp.tensile_r, work.grad_c.data(),
            work.div_r.data(), sp.mode, work.near_wall.data()),
        work.lists);
  };
  if (sp.mode == ShiftMode::Full)
    pass1(std::false_type{});
  else
    pass1(std::true_type{});
  const double threshold = sp.threshold(D);
  const double ah_dt = sp.coefficient * kernel.h * dt;
  std::size_t surface = 0, skipped = 0, near_wall = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : surface, skipped, near_wall)
  for (long i = 0; i < n; ++i) {
    const auto a = static_cast<std::size_t>(i);
    normal[a].setZero();
    shift[a].setZero();
    if (ps.role[a] != Role::Fluid) continue;
    const double diffusion = ah_dt * ps.velocity(a).norm();
    if (!(diffusion > 0.0)) continue;
    if (work.near_wall[a]) {  // the mode leaves it where it is (its normal stays 0)
      ++near_wall;
      continue;
    }
    shift[a] = -diffusion * work.grad_c[a];
    if (!(work.div_r[a] < threshold)) continue;
    ++surface;
    ShiftingTerms<D> t;
    for_each_shifting_pair<D>(ps, grid, kernel, a,
                              [&](std::uint32_t b, const Vec<D>& r, double, double dist) {
                                const double vf = vol[b] * kernel.f(dist);
                                t.grad_c0 += vf * r;
                                t.b -= vf * r * r.transpose();
                              });
    bool skip = false;
    normal[a] = surface_normal<D>(t, skip);
    if (skip) {
      ++skipped;
      shift[a].setZero();
    } else {
      shift[a] -= shift[a].dot(normal[a]) * normal[a];
    }
  }
  // Cells holding a surface particle (serial: a byte per surface particle).
  std::fill(work.cell_flag.begin(), work.cell_flag.begin() + static_cast<long>(grid.num_cells()),
            std::uint8_t{0});
  for (std::size_t a = 0; a < np; ++a)
    if (normal[a].squaredNorm() > 0.0) work.cell_flag[grid.cell_of(a)] = 1;
  remote_normals(normal, gb);  // halo images of a decomposed run: their owners' normals
  for (std::size_t k = 0; k < ns - gb; ++k) {  // periodic images carry their source's normal
    if (grid.ghost_source(k) != CellGrid<D>::kRemote) normal[gb + k] = normal[grid.ghost_source(k)];
    if (normal[gb + k].squaredNorm() > 0.0) work.cell_flag[grid.ghost_cell(k)] = 1;
  }
  std::size_t shifted = 0;
  double max2 = 0.0;
  const std::vector<std::uint8_t>& flag = work.cell_flag;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : shifted) reduction(max : max2)
  for (long i = 0; i < n; ++i) {
    const auto a = static_cast<std::size_t>(i);
    if (ps.role[a] != Role::Fluid) continue;
    if (normal[a].squaredNorm() == 0.0 && shift[a].squaredNorm() > 0.0) {
      bool near = false;
      grid.for_each_neighbour_row(grid.cell_of(a), [&](std::size_t row) {
        near = near || flag[row - 1] || flag[row] || flag[row + 1];
      });
      if (near) {
        Vec<D> m = Vec<D>::Zero();
        for_each_shifting_pair<D>(ps, grid, kernel, a,
                                  [&](std::uint32_t b, const Vec<D>&, double, double dist) {
                                    if (normal[b].squaredNorm() > 0.0)
                                      m += kernel.w(dist) * normal[b];
                                  });
        const double len = m.norm();
        if (len > 0.0) {
          const Vec<D> u = m / len;
          shift[a] -= shift[a].dot(u) * u;
        }
      }
    }
    const double d2 = shift[a].squaredNorm();
    shifted += d2 > 0.0;
    max2 = std::max(max2, d2);
  }
  if (sp.correct_density) {
    // dr . grad rho from the densities before any shift (applied by the caller with the
    // shift, so no particle reads a neighbour's corrected density).
    if (work.drho.size() < np) work.drho.resize(np);
    const auto near = [&](const Vec<D>& x, auto&& fn) { grid.for_each_candidate_near(x, fn); };
    const auto fluid = [&](std::uint32_t b) { return ps.role[b] == Role::Fluid; };
    const auto rho = [&](std::uint32_t b) -> double { return ps.rho[b]; };
#pragma omp parallel for schedule(dynamic, 256)
    for (long i = 0; i < n; ++i) {
      const auto a = static_cast<std::uint32_t>(i);
      work.drho[a] = 0.0;
      if (ps.role[a] != Role::Fluid || !(shift[a].squaredNorm() > 0.0)) continue;
      const Eigen::Matrix<double, D, D> L = kgc_matrix<D>(ps, kernel, near, a, fluid, 0.1);
      work.drho[a] = shift[a].dot(gradient_at_particle<D>(ps, kernel, near, a, rho, L));
    }
  }
  return {shifted, surface, skipped, near_wall, std::sqrt(max2)};
}

}  // namespace swell
