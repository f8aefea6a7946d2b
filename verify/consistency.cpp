// `consistency`: the operators of solver/physics/corrections.hpp on the linear field
// f = 1 + 2 x - 3 y (- z in 3D), on a lattice, on lattices with 10, 20 and 30 % random
// displacement, and at a free surface (a half-filled box, evaluated within one support of the
// top). Errors are the largest over the evaluation particles, relative to |grad f| (gradients)
// or to the range of f (values).
#include <algorithm>
#include <cmath>
#include <string>

#include "solver/physics/corrections.hpp"
#include "solver/physics/kernels.hpp"
#include "verify/cloud.hpp"
#include "verify/operators.hpp"

namespace swell::verify {
namespace {

template <int D>
Vec<D> slope() {
  Vec<D> c;
  c[0] = 2.0;
  c[1] = -3.0;
  if constexpr (D == 3) c[2] = -1.0;
  return c;
}

struct Errors {
  double grad_plain = 0, grad_kgc = 0, grad_liu = 0;  // relative to |grad f|
  double val_shepard = 0, val_liu = 0, val_mls = 0;   // relative to the range of f
  int points = 0;
};

// surface = false: particles whose support lies inside the set; true: particles within one
// support below the top of a set filled to half height (a free surface above them).
template <int D>
Errors measure(int n, double jitter, bool surface, std::uint32_t seed) {
  const double coefh = 1.0;  // h = coefh sqrt(D) dp, the solver's default
  const WendlandC2<D> kernel(coefh * std::sqrt(double(D)) / n);
  const Cloud<D> c =
      make_cloud<D>(n, coefh * std::sqrt(double(D)), 2.0, jitter, seed, surface ? 0.5 : 1.0);
  const Vec<D> k = slope<D>();
  auto f = [&](std::uint32_t b) { return 1.0 + k.dot(c.ps.pos[b]); };
  const double range = k.cwiseAbs().sum();
  const double s = kernel.support();
  const double top = surface ? 0.5 : 1.0;
  auto near = c.near();
  auto fluid = [&](std::uint32_t b) { return c.ps.role[b] == Role::Fluid; };
  Errors e;
  for (std::uint32_t a = 0; a < c.ps.size(); ++a) {
    const Vec<D>& x = c.ps.pos[a];
    bool use = true;
    for (int d = 0; d < D; ++d) {
      const double hi = d == D - 1 ? top : 1.0;
      if (surface && d == D - 1)
        use = use && x[d] > hi - s && x[d] < hi;  // within one support of the surface
      else
        use = use && x[d] > s && x[d] < hi - s;
    }
    if (!use) continue;
    ++e.points;
    const double fx = 1.0 + k.dot(x);
    const Eigen::Matrix<double, D, D> I = Eigen::Matrix<double, D, D>::Identity();
    const Vec<D> g0 = gradient_at_particle<D>(c.ps, kernel, near, a, f, I);
    const auto L = kgc_matrix<D>(c.ps, kernel, near, a, fluid, 1e-12);
    const Vec<D> g1 = gradient_at_particle<D>(c.ps, kernel, near, a, f, L);
    const auto cv = corrected_at<D>(c.ps, kernel, near, x, f, 1e-12);
    const double sh = shepard_at<D>(c.ps, kernel, near, x, f);
    const double mls = mls_at<D>(c.ps, kernel, near, x, f, 1e-12);
    e.grad_plain = std::max(e.grad_plain, (g0 - k).norm() / k.norm());
    e.grad_kgc = std::max(e.grad_kgc, (g1 - k).norm() / k.norm());
    e.grad_liu = std::max(e.grad_liu, (cv.grad - k).norm() / k.norm());
    e.val_shepard = std::max(e.val_shepard, std::abs(sh - fx) / range);
    e.val_liu = std::max(e.val_liu, std::abs(cv.value - fx) / range);
    e.val_mls = std::max(e.val_mls, std::abs(mls - fx) / range);
  }
  return e;
}

}  // namespace

Result run_consistency(const Options& opt) {
  Result r;
  const int n2 = opt.full ? 80 : 40, n3 = opt.full ? 24 : 14;
  // Round-off bound for the corrected operators: a (D+1) x (D+1) solve with condition numbers
  // of O(10-100) on sums of O(100) terms of O(1): 1e-10 leaves 4-5 digits of margin.
  const double exact = 1e-10;
  Table t{"linear_field_errors",
          {"dim", "jitter [dp]", "surface", "points", "grad plain", "grad kgc", "grad liu",
           "value shepard", "value liu", "value mls"},
          {}};
  struct Set {
    int dim;
    double jitter;
    bool surface;
    const char* label;
  };
  const Set sets[] = {{2, 0.0, false, "2D lattice"},       {2, 0.1, false, "2D 10 % disorder"},
                      {2, 0.2, false, "2D 20 % disorder"}, {2, 0.3, false, "2D 30 % disorder"},
                      {2, 0.0, true, "2D free surface"},   {2, 0.2, true, "2D free surface, 20 %"},
                      {3, 0.2, false, "3D 20 % disorder"}, {3, 0.0, true, "3D free surface"}};
  for (const Set& s : sets) {
    const Errors e = s.dim == 2 ? measure<2>(n2, s.jitter, s.surface, 7)
                                : measure<3>(n3, s.jitter, s.surface, 7);
    const std::string L = s.label;
    t.rows.push_back({double(s.dim), s.jitter, s.surface ? 1.0 : 0.0, double(e.points),
                      e.grad_plain, e.grad_kgc, e.grad_liu, e.val_shepard, e.val_liu, e.val_mls});
    r.figures.push_back(at_most(L + ": KGC gradient error", e.grad_kgc, exact));
    r.figures.push_back(at_most(L + ": Liu & Liu gradient error", e.grad_liu, exact));
    r.figures.push_back(at_most(L + ": Liu & Liu value error", e.val_liu, exact));
    r.figures.push_back(at_most(L + ": MLS value error", e.val_mls, exact));
    // The uncorrected operators are not exact where the support is disordered or cut: they
    // must show an error well above round-off (else this check could not tell them apart).
    if (s.jitter > 0.0 || s.surface)
      r.figures.push_back(at_least(L + ": uncorrected gradient error", e.grad_plain, 1e-3));
    else
      r.figures.push_back(report(L + ": uncorrected gradient error", e.grad_plain));
    if (s.surface)
      r.figures.push_back(at_least(L + ": Shepard value error", e.val_shepard, 1e-3));
    else
      r.figures.push_back(report(L + ": Shepard value error", e.val_shepard));
  }
  r.tables.push_back(t);
  r.notes =
      "Linear field f = 1 + 2x - 3y (- z in 3D) on [0,1]^D particle sets (2D: " +
      std::to_string(n2) + "^2, 3D: " + std::to_string(n3) +
      "^3; Wendland C2, h = sqrt(D) dp), each particle displaced by up to the stated fraction "
      "of dp per axis. Errors: the largest over the particles whose support lies inside the set "
      "(or, for the free surface, over the particles within one support below the top of a "
      "half-filled box), relative to |grad f| for gradients and to the range of f for values. "
      "Corrected operators (kernel gradient correction L_a, Liu & Liu's first-order system, "
      "first-order MLS) must be exact to round-off; the uncorrected difference-form gradient "
      "and the Shepard value must not be (they are exact only for full, symmetric supports).";
  return r;
}

}  // namespace swell::verify
