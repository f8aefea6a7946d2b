// Conservation by construction: the symmetric momentum equation makes every pair force
// antisymmetric, so a closed set of fluid particles (no gravity, no walls) keeps its total
// linear momentum to round-off; masses never change.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bc/dbc.hpp"
#include "solver/diagnostics.hpp"
#include "solver/time/simulation.hpp"
#include "tests/state_precision.hpp"
#include "verify/pair_rounding.hpp"

namespace swell {
namespace {

template <int D>
ParticleSet<D> random_block(int n_side, double dp, double rho0, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ParticleSet<D> ps;
  const int nz = D == 3 ? n_side : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n_side; ++j)
      for (int i = 0; i < n_side; ++i) {
        Vec<D> x, v;
        x[0] = (i + 0.5) * dp + 0.05 * dp * u(rng);
        x[1] = (j + 0.5) * dp + 0.05 * dp * u(rng);
        if constexpr (D == 3) x[2] = (k + 0.5) * dp + 0.05 * dp * u(rng);
        for (int d = 0; d < D; ++d) v[d] = 0.5 * u(rng);
        // Density perturbed by +-1% so pressures differ between particles.
        ps.add(x, v, rho0 * (1.0 + 0.01 * u(rng)), rho0 * std::pow(dp, D) * (1.0 + 0.2 * u(rng)),
               Role::Fluid, 0);
      }
  return ps;
}

template <int D>
SolverParams free_params(double dp, int n_side, IntegratorType integ, ViscosityModel visc) {
  SolverParams p;
  p.dp = dp;
  p.h = std::sqrt(double(D)) * dp;
  p.gravity.setZero();
  p.c0 = 20.0;
  p.integrator = integ;
  p.viscosity = visc;
  p.alpha = 0.1;
  p.nu = 1e-3;
  p.domain_min = Eigen::Vector3d::Constant(-2.0 * n_side * dp);
  p.domain_max = Eigen::Vector3d::Constant(3.0 * n_side * dp);
  return p;
}

template <int D>
void check_momentum(IntegratorType integ, ViscosityModel visc) {
  const double dp = 0.01;
  const int n_side = D == 2 ? 24 : 10;
  Simulation<D> sim(free_params<D>(dp, n_side, integ, visc), random_block<D>(n_side, dp, 1000.0, 7),
                    make_dbc<D>());
  const auto before = fluid_totals(sim.particles());
  const auto mass_by_id = [&sim]() {
    std::vector<double> m(sim.particles().total());
    for (std::size_t i = 0; i < sim.particles().size(); ++i)
      m[sim.particles().id[i]] = sim.particles().mass[i];
    return m;
  };
  const std::vector<double> mass0 = mass_by_id();
  double scale = 0.0;  // sum m |v|: the size of the numbers whose round-off we accept
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    scale += sim.particles().mass[i] * sim.particles().velocity(i).norm();
  double pair_drift = 0.0;  // what the pair loop's float rounding may add to the drift
  for (int s = 0; s < 100; ++s) {
    sim.step();
    // The pair terms are exactly antisymmetric: the rates' momentum sum m a is zero up to the
    // summation order, at every step, and up to the rounding of the pair loop's arithmetic
    // (float unless the double-state build; verify/pair_rounding.hpp, taken at the step's end
    // state, which differs from the evaluation's by O(dt)).
    const auto& q = sim.particles();
    Vec<D> sum_ma = Vec<D>::Zero();
    double abs_ma = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      sum_ma += q.mass[i] * sim.acceleration()[i];
      abs_ma += q.mass[i] * sim.acceleration()[i].norm();
    }
    const double pair = std::sqrt(double(D)) * pair_rounding<D>(q, sim.params()).momentum(q);
    ASSERT_LT(sum_ma.norm(), 1e-12 * abs_ma + pair) << "step " << s;
    pair_drift += sim.dt() * pair;
  }
  const auto after = fluid_totals(sim.particles());
  EXPECT_EQ(sim.excluded().total(), 0u);
  EXPECT_EQ(after.count, before.count);
  // The sorts reordered the float fields through the force buffers, no scratch of their own.
  EXPECT_EQ(sim.particles().raw_scratch_bytes(), 0u);
  // Exactly, particle by particle: masses are never modified (the summed total may differ in
  // the last bit only because the sort changes the summation order).
  EXPECT_EQ(mass_by_id(), mass0);
  EXPECT_NEAR(after.mass, before.mass, 1e-14 * before.mass);
  const double drift = (after.momentum - before.momentum).norm();
  std::cout << "  " << D << "D momentum drift over 100 steps: " << drift << " (scale " << scale
            << ", relative " << drift / scale << ")\n";
  // Every pair term is exactly antisymmetric; only the summation order differs between the
  // two particles of a pair, so the drift is a few ulps of the momentum scale per step, plus
  // the rounding of the stored velocities (tests/state_precision.hpp) and of the pair loop's
  // float arithmetic (dt times the per-step bound above).
  EXPECT_LT(drift, 1e-12 * scale + momentum_rounding(scale, 100) + pair_drift);
  // The particles did move and interact (the test is not vacuous).
  EXPECT_GT((after.momentum - before.momentum).norm() +
                std::abs(after.kinetic_energy - before.kinetic_energy),
            0.0);
  EXPECT_NE(after.kinetic_energy, before.kinetic_energy);
}

TEST(Conservation, Momentum2DSymplecticArtificial) {
  check_momentum<2>(IntegratorType::Symplectic, ViscosityModel::Artificial);
}
TEST(Conservation, Momentum2DVerletLaminar) {
  check_momentum<2>(IntegratorType::Verlet, ViscosityModel::Laminar);
}
TEST(Conservation, Momentum3DSymplecticArtificial) {
  check_momentum<3>(IntegratorType::Symplectic, ViscosityModel::Artificial);
}
TEST(Conservation, Momentum3DVerletArtificial) {
  check_momentum<3>(IntegratorType::Verlet, ViscosityModel::Artificial);
}

// A step that excludes a fluid particle for its density re-sorts the particles after the
// integration; the accelerations and density rates of the step (wall loads and output read
// them between steps) must be rearranged with them. Verlet's first step makes
// v = v_prev + 2 dt a and rho = rho_prev + 2 dt drho for every fluid particle, which ties each
// particle's rates to its own state.
TEST(Exclusion, RatesFollowTheSortAfterADensityExclusion) {
  const double dp = 0.01;
  const int n_side = 24;
  ParticleSet<2> ps = random_block<2>(n_side, dp, 1000.0, 11);
  ps.rho[300] = ps.rho_prev[300] = 1350.0;  // beyond rho_max_factor 1.3: excluded in step 1
  Simulation<2> sim(free_params<2>(dp, n_side, IntegratorType::Verlet, ViscosityModel::Artificial),
                    std::move(ps), make_dbc<2>());
  sim.step();
  ASSERT_EQ(sim.excluded().density_out_of_range, 1u);
  const auto& p = sim.particles();
  const double dt = sim.dt();
  std::size_t moved = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    moved += p.id[i] != i ? 1 : 0;
    // (the new v and rho are rounded once when stored: stored_tol)
    const Vec<2> dv = p.velocity(i) - widen<2>(p.vel_prev[i]),
                 expect = 2.0 * dt * sim.acceleration()[i];
    ASSERT_NEAR((dv - expect).norm(), 0.0,
                stored_tol(p.velocity(i).norm(), 1e-12 * (1.0 + expect.norm())))
        << "particle id " << p.id[i];
    const double drho = double(p.rho[i]) - double(p.rho_prev[i]),
                 expect_rho = 2.0 * dt * sim.density_rate()[i];
    ASSERT_NEAR(drho, expect_rho, stored_tol(p.rho[i], 1e-9)) << "particle id " << p.id[i];
  }
  EXPECT_GT(moved, 0u);  // the sorts did rearrange the arrays
}

}  // namespace
}  // namespace swell
