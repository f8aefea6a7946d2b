// The fast forms of the operator verifications (verify/operators.hpp) and the correction hooks
// of solver/time/correction_hooks.hpp.
#include <gtest/gtest.h>

#include <iostream>

#include "solver/physics/corrections.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/time/correction_hooks.hpp"
#include "tests/state_precision.hpp"
#include "verify/angular_momentum.hpp"
#include "verify/cloud.hpp"
#include "verify/operators.hpp"

namespace swell {
namespace {

void expect_passes(const verify::Result& r) {
  ASSERT_FALSE(r.figures.empty());
  for (const auto& f : r.figures) {
    std::cout << "  " << f.name << " = " << f.value << (f.pass() ? "" : "   <-- FAILS") << "\n";
    EXPECT_TRUE(f.pass()) << f.name << " = " << f.value << " (bound " << f.bound << ")";
  }
}

TEST(VerifyOperators, Consistency) {
  expect_passes(verify::run_consistency({}));
}
TEST(VerifyOperators, GradientConvergence) {
  expect_passes(verify::run_gradient_convergence({}));
}
TEST(VerifyOperators, Laplacian) {
  expect_passes(verify::run_laplacian({}));
}
TEST(VerifyOperators, Kernels) {
  expect_passes(verify::run_kernels({}));
}

// The Shepard re-initialisation sets every fluid density to the Shepard average of the old
// densities (a Jacobi update), only at the step after every N-th, and carries its counter
// through save/restore.
TEST(CorrectionHooks, ShepardReinitEveryNSteps) {
  auto c = verify::make_cloud<2>(20, std::sqrt(2.0), 2.0, 0.2, 11);
  for (std::size_t i = 0; i < c.ps.size(); ++i) c.ps.rho[i] = 1.0 + 0.1 * std::sin(7.0 * i);
  const auto old = c.ps.rho;
  SolverParams p;
  p.h = c.h;
  ForceBuffers<2> fb;
  TaitEos eos(1.0, 1.0, 7.0);
  StepState<2> s{c.ps, c.grid, fb, p, eos, 0.0, 0.0};
  ShepardReinit<2> hook(3);
  hook.after_integration(s);
  hook.after_integration(s);
  hook.before_forces(s);
  EXPECT_EQ(c.ps.rho, old);  // not yet
  std::map<std::string, double> saved;
  hook.after_integration(s);  // third step: due
  hook.save(saved);
  ShepardReinit<2> restored(3);
  restored.restore(saved);
  restored.before_forces(s);
  EXPECT_EQ(restored.reinitialisations(), 1);
  const WendlandC2<2> kernel(c.h);
  auto near = c.near();
  ParticleSet<2> ref = c.ps;
  ref.rho = old;
  for (std::uint32_t a = 0; a < c.ps.size(); ++a) {
    const double expect =
        shepard_at<2>(ref, kernel, near, ref.pos[a], [&](std::uint32_t b) { return old[b]; });
    ASSERT_NEAR(c.ps.rho[a], expect, stored_tol(expect, 1e-14 * expect));  // stored once
  }
}

// The corrected momentum equation: for a linear pressure field on a disordered set, L_a times
// the pressure sum gives the exact pressure gradient at interior particles, which the plain sum
// does not.
TEST(CorrectionHooks, KgcMakesALinearPressureGradientExact) {
  auto c = verify::make_cloud<2>(30, std::sqrt(2.0), 2.0, 0.2, 5);
  SolverParams p;
  p.h = c.h;
  p.gravity = Eigen::Vector3d(0.0, -9.81, 0.0);
  const WendlandC2<2> kernel(c.h);
  auto near = c.near();
  ForceBuffers<2> fb;
  fb.resize(c.ps.size());
  // dv/dt = -sum_b V_b (p_b - p_a) gradW_ab (difference form, rho = 1) + g, p = 1 + 3 x + 2 y.
  auto pf = [&](std::uint32_t b) { return 1.0 + 3.0 * c.ps.pos[b][0] + 2.0 * c.ps.pos[b][1]; };
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  for (std::uint32_t a = 0; a < c.ps.size(); ++a)
    fb.ace[a] = -gradient_at_particle<2>(c.ps, kernel, near, a, pf, I) + Vec<2>(0.0, -9.81);
  const auto plain = fb.ace;
  TaitEos eos(1.0, 1.0, 7.0);
  StepState<2> s{c.ps, c.grid, fb, p, eos, 0.0, 0.0};
  KernelGradientCorrection<2> hook(0.1);
  hook.after_forces(s);
  EXPECT_GT(hook.corrected(), c.ps.size() * 8 / 10);  // all but the corners and edges
  const Vec<2> exact(-3.0, -2.0 - 9.81);
  double worst_plain = 0.0, worst = 0.0;
  for (std::uint32_t a = 0; a < c.ps.size(); ++a) {
    const Vec<2>& x = c.ps.pos[a];
    if (!(x.minCoeff() > 2.0 * c.h && x.maxCoeff() < 1.0 - 2.0 * c.h)) continue;
    worst = std::max(worst, (fb.ace[a] - exact).norm());
    worst_plain = std::max(worst_plain, (plain[a] - exact).norm());
  }
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(worst_plain, 1e-2);
}

}  // namespace
}  // namespace swell

namespace swell {
namespace {
TEST(VerifyOperators, AngularMomentum) {
  expect_passes(verify::run_angular_momentum({}));
}
}  // namespace
}  // namespace swell
