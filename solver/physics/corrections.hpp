// Interpolation operators and kernel corrections of the SPH course (issue #14), written once and
// used by mDBC's ghost nodes (bc/mdbc), the kernel-gradient-corrected momentum equation
// (solver/time/correction_hooks.hpp), the Shepard density re-initialisation, point probes and
// `swell verify`. Every operator sums over the FLUID particles near a point; `near(x, fn)` is
// any visitor that calls fn(j) for at least every particle j within the kernel support of x
// (CellGrid::for_each_candidate_near, or a scan of all particles).
//
//   Shepard (1968), zeroth order:  f(x) = sum_b f_b V_b W_b / sum_b V_b W_b   (V_b = m_b / rho_b)
//     reproduces constants exactly, linear fields only where the support is full and symmetric.
//   First-order consistent (Liu & Liu 2006, Comput. Mech.; as mDBC, English et al. 2022):
//     sum_b V_b [ W_b, (x_b - x)^T W_b ; gradW_b, gradW_b (x_b - x)^T ] [f; grad f]
//        = sum_b V_b f_b [ W_b ; gradW_b ]
//     ((D+1) x (D+1), solved with Eigen): value and gradient exact for linear fields wherever the
//     matrix is invertible; a Shepard value (no gradient) where |det| < det_min.
//   Moving least squares, first order (Lancaster & Salkauskas 1981; Dilts 1999):
//     f(x) = p(0)^T M^-1 sum_b V_b W_b p_b f_b,  M = sum_b V_b W_b p_b p_b^T,  p_b = [1, x_b - x]:
//     the value of the weighted least-squares linear fit; exact for linear fields.
//   Kernel gradient correction (Bonet & Lok 1999; Randles & Libersky 1996):
//     L_a = [ sum_b V_b gradW_ab (x_b - x_a)^T ]^-1,  grad f_a = L_a sum_b V_b (f_b - f_a)
//     gradW_ab, exact for linear fields where the moment matrix is invertible (identity where |det|
//     is below det_min: isolated or splashing particles).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <limits>

#include "solver/state/particle_set.hpp"

namespace swell {

// How a corrected value was obtained.
enum class CorrectionMode : std::uint8_t { Dry = 0, Shepard = 1, Corrected = 2 };

// The first-order consistent system of Liu & Liu (2006) at one point, for M right-hand sides
// (column j of B: the volume-weighted sums of the j-th field). add_moments() adds a neighbour's
// row of the matrix; the caller adds its right-hand sides (add_value, or directly into B).
template <int D, int M>
struct FirstOrderSystem {
  using Matrix = Eigen::Matrix<double, D + 1, D + 1>;
  using Rhs = Eigen::Matrix<double, D + 1, M>;
  Matrix A = Matrix::Zero();
  Rhs B = Rhs::Zero();

  // Neighbour b: V = V_b, w = W(x - x_b), gw = grad_x W(x - x_b), r = x - x_b.
  void add_moments(double V, double w, const Vec<D>& gw, const Vec<D>& r) {
    A(0, 0) += w * V;
    A.template block<1, D>(0, 1) -= (w * V) * r.transpose();  // (x_b - x) W V
    A.template block<D, 1>(1, 0) += V * gw;
    A.template block<D, D>(1, 1) -= V * gw * r.transpose();  // gradW (x_b - x)^T V
  }
  // Field value f of neighbour b into right-hand side j.
  void add_value(int j, double V, double w, const Vec<D>& gw, double f) {
    B(0, j) += (w * V) * f;
    B.template block<D, 1>(1, j) += (V * gw) * f;
  }

  struct Solution {
    Rhs X = Rhs::Zero();  // row 0: the values; rows 1..D: their gradients (Corrected only)
    double det = 0.0;
    CorrectionMode mode = CorrectionMode::Dry;
  };
  Solution solve(double det_min) const {
    Solution s;
    if (!(A(0, 0) > 0.0)) return s;  // no fluid in reach
    s.det = A.determinant();
    if (std::abs(s.det) >= det_min) {
      s.X = A.inverse() * B;
      s.mode = CorrectionMode::Corrected;
    } else {
      s.X.row(0) = B.row(0) / A(0, 0);
      s.mode = CorrectionMode::Shepard;
    }
    return s;
  }
};

// Shepard interpolation at x of the field f(j) (a callable), over fluid particles. NaN when dry.
template <int D, class Kernel, class Near, class F>
double shepard_at(const ParticleSet<D>& ps, const Kernel& kernel, Near&& near, const Vec<D>& x,
                  F&& f) {
  const double s2 = kernel.support() * kernel.support();
  double sum_f = 0.0, sum_w = 0.0;
  near(x, [&](std::uint32_t b) {
    if (ps.role[b] != Role::Fluid) return;
    const double r2 = (x - ps.pos[b]).squaredNorm();
    if (!(r2 < s2)) return;
    const double wv = kernel.w(std::sqrt(r2)) * ps.mass[b] / ps.rho[b];
    sum_f += f(b) * wv;
    sum_w += wv;
  });
  return sum_w > 0.0 ? sum_f / sum_w : std::numeric_limits<double>::quiet_NaN();
}

template <int D>
struct CorrectedValue {
  double value = std::numeric_limits<double>::quiet_NaN();
  Vec<D> grad = Vec<D>::Constant(std::numeric_limits<double>::quiet_NaN());
  double det = 0.0;
  CorrectionMode mode = CorrectionMode::Dry;
};

// Liu & Liu first-order corrected value and gradient at x of the field f(j).
template <int D, class Kernel, class Near, class F>
CorrectedValue<D> corrected_at(const ParticleSet<D>& ps, const Kernel& kernel, Near&& near,
                               const Vec<D>& x, F&& f, double det_min) {
  FirstOrderSystem<D, 1> sys;
  const double s2 = kernel.support() * kernel.support();
  near(x, [&](std::uint32_t b) {
    if (ps.role[b] != Role::Fluid) return;
    const Vec<D> r = x - ps.pos[b];
    const double r2 = r.squaredNorm();
    if (!(r2 < s2)) return;
    const double dist = std::sqrt(r2);
    const double w = kernel.w(dist);
    const Vec<D> gw = r * kernel.f(dist);
    const double V = ps.mass[b] / ps.rho[b];
    sys.add_moments(V, w, gw, r);
    sys.add_value(0, V, w, gw, f(b));
  });
  const auto s = sys.solve(det_min);
  CorrectedValue<D> out;
  out.det = s.det;
  out.mode = s.mode;
  if (s.mode == CorrectionMode::Dry) return out;
  out.value = s.X(0, 0);
  if (s.mode == CorrectionMode::Corrected) out.grad = s.X.template block<D, 1>(1, 0);
  return out;
}

// First-order moving-least-squares value at x of the field f(j). Where the moment matrix is
// singular (|det| < det_min, e.g. fewer than D + 1 non-collinear neighbours) the Shepard value.
template <int D, class Kernel, class Near, class F>
double mls_at(const ParticleSet<D>& ps, const Kernel& kernel, Near&& near, const Vec<D>& x, F&& f,
              double det_min) {
  using P = Eigen::Matrix<double, D + 1, 1>;
  Eigen::Matrix<double, D + 1, D + 1> Mm = Eigen::Matrix<double, D + 1, D + 1>::Zero();
  P rhs = P::Zero();
  const double s2 = kernel.support() * kernel.support();
  // The basis is scaled by 1/h so the moment matrix is dimensionless (det_min means the same at
  // every resolution).
  const double inv_h = 1.0 / kernel.h;
  near(x, [&](std::uint32_t b) {
    if (ps.role[b] != Role::Fluid) return;
    const Vec<D> d = ps.pos[b] - x;
    const double r2 = d.squaredNorm();
    if (!(r2 < s2)) return;
    P p;
    p(0) = 1.0;
    p.template tail<D>() = d * inv_h;
    const double wv = kernel.w(std::sqrt(r2)) * ps.mass[b] / ps.rho[b];
    Mm += (wv * p) * p.transpose();
    rhs += (wv * f(b)) * p;
  });
  if (!(Mm(0, 0) > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // Normalised by the zeroth moment (the Shepard denominator) so det_min is scale-free.
  const double det = (Mm / Mm(0, 0)).determinant();
  if (std::abs(det) < det_min) return rhs(0) / Mm(0, 0);
  return Mm.ldlt().solve(rhs)(0);
}

// Calls fn(b, r_ab, r_ab^2) for every particle b != a that `near` visits, `use(b)` accepts and
// that lies within the kernel support of a (r_ab = x_a - x_b, never zero): the neighbour loop
// the per-particle operators below share.
template <int D, class Kernel, class Near, class Use, class Fn>
void for_each_support_neighbour(const ParticleSet<D>& ps, const Kernel& kernel, Near&& near,
                                std::uint32_t a, Use&& use, Fn&& fn) {
  const double s2 = kernel.support() * kernel.support();
  const Vec<D> xa = ps.pos[a];
  near(xa, [&](std::uint32_t b) {
    if (b == a || !use(b)) return;
    const Vec<D> r = xa - ps.pos[b];  // r_ab
    const double r2 = r.squaredNorm();
    if (!(r2 < s2) || !(r2 > 0.0)) return;
    fn(b, r, r2);
  });
}

// The kernel-gradient correction matrix of particle a (over the particles `near` visits and
// `use(b)` accepts, b != a), and the determinant of the moment matrix it inverts. Where
// |det| < det_min the identity (no correction).
template <int D, class Kernel, class Near, class Use>
Eigen::Matrix<double, D, D> kgc_matrix(const ParticleSet<D>& ps, const Kernel& kernel, Near&& near,
                                       std::uint32_t a, Use&& use, double det_min,
                                       double* det_out = nullptr) {
  using Mat = Eigen::Matrix<double, D, D>;
  Mat Mm = Mat::Zero();
  for_each_support_neighbour(
      ps, kernel, near, a, use, [&](std::uint32_t b, const Vec<D>& r, double r2) {
        const Vec<D> gw = r * kernel.f(std::sqrt(r2));        // grad_a W_ab
        Mm -= (ps.mass[b] / ps.rho[b]) * gw * r.transpose();  // V_b gradW_ab (x_b - x_a)^T
      });
  const double det = Mm.determinant();
  if (det_out) *det_out = det;
  if (!(std::abs(det) >= det_min)) return Mat::Identity();
  return Mm.inverse();
}

// The SPH gradient of f at particle a in the difference form sum_b V_b (f_b - f_a) gradW_ab over
// fluid neighbours, multiplied by L (the identity: uncorrected; kgc_matrix: corrected).
template <int D, class Kernel, class Near, class F>
Vec<D> gradient_at_particle(const ParticleSet<D>& ps, const Kernel& kernel, Near&& near,
                            std::uint32_t a, F&& f, const Eigen::Matrix<double, D, D>& L) {
  Vec<D> g = Vec<D>::Zero();
  const double fa = f(a);
  const auto fluid = [&](std::uint32_t b) { return ps.role[b] == Role::Fluid; };
  for_each_support_neighbour(
      ps, kernel, near, a, fluid, [&](std::uint32_t b, const Vec<D>& r, double r2) {
        g += ((ps.mass[b] / ps.rho[b]) * (f(b) - fa) * kernel.f(std::sqrt(r2))) * r;
      });
  return L * g;
}

// The SPH Laplacian of f at particle a in Morris et al.'s (1997) form, the scalar form of the
// laminar viscous term (solver/physics/viscosity.hpp, Lo & Shao 2002):
//   lap f_a = sum_b 2 V_b (f_a - f_b) (r_ab . gradW_ab) / (r_ab^2 + eta^2),  eta^2 = 0.01 h^2.
template <int D, class Kernel, class Near, class F>
double laplacian_at_particle(const ParticleSet<D>& ps, const Kernel& kernel, Near&& near,
                             std::uint32_t a, F&& f) {
  double lap = 0.0;
  const double eta2 = 0.01 * kernel.h * kernel.h;
  const double fa = f(a);
  const auto fluid = [&](std::uint32_t b) { return ps.role[b] == Role::Fluid; };
  for_each_support_neighbour(
      ps, kernel, near, a, fluid, [&](std::uint32_t b, const Vec<D>&, double r2) {
        const double r_dot_gw = r2 * kernel.f(std::sqrt(r2));
        lap += 2.0 * (ps.mass[b] / ps.rho[b]) * (fa - f(b)) * r_dot_gw / (r2 + eta2);
      });
  return lap;
}

}  // namespace swell
