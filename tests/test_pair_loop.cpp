// The vectorised pair loop (neighbours/pair_driver.hpp + physics/wcsph_evaluator.hpp: packed
// neighbour lists, padding, wall flag in the list entry, DBC's wall selection) against a
// brute-force O(N^2) evaluation of the same equations written with the value types of
// solver/physics/ in vector form and the kernels' branchy f(r). Random particles (jittered lattice
// with gaps, walls mixed in, random velocities and densities), every kernel, both viscosity models,
// the three diffusion settings, 2D and 3D.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <iostream>
#include <random>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/physics/density_diffusion.hpp"
#include "solver/physics/viscosity.hpp"
#include "solver/physics/wcsph_forces.hpp"
#include "verify/pair_rounding.hpp"

namespace swell {
namespace {

template <int D>
ParticleSet<D> random_particles(int n_side, double dp, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
  ParticleSet<D> ps;
  const int nz = D == 3 ? n_side : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n_side; ++j)
      for (int i = 0; i < n_side; ++i) {
        if (u01(rng) < 0.1) continue;  // gaps: partly filled supports, free surfaces
        Vec<D> x, v;
        x[0] = (i + 0.5) * dp + 0.2 * dp * u(rng);
        x[1] = (j + 0.5) * dp + 0.2 * dp * u(rng);
        if constexpr (D == 3) x[2] = (k + 0.5) * dp + 0.2 * dp * u(rng);
        for (int d = 0; d < D; ++d) v[d] = 0.5 * u(rng);
        // Walls: the bottom two layers and a sprinkling inside.
        const bool wall = j < 2 || u01(rng) < 0.08;
        if (wall) v.setZero();
        ps.add(x, v, 1000.0 * (1.0 + 0.02 * u(rng)),
               1000.0 * std::pow(dp, D) * (1.0 + 0.1 * u(rng)),
               wall ? Role::FixedWall : Role::Fluid, 0);
      }
  // One particle exactly on top of another: a coincident pair is skipped by both loops.
  ps.add(ps.pos[ps.size() / 2], Vec<D>::Zero(), 1000.0, 1000.0 * std::pow(dp, D), Role::Fluid, 0);
  return ps;
}

struct Reference {
  std::vector<double> drho;
  std::vector<Eigen::Vector3d> ace;
  double visc_dt_max = 0.0;
};

template <int D, class K>
Reference brute_force(const ParticleSet<D>& ps, const K& kernel, const SolverParams& p) {
  const TaitEos eos(p.rho0, p.c0, p.gamma);
  const ArtificialViscosity av{p.alpha, p.h};
  const LaminarViscosity lam{4.0 * p.nu};
  const DensityDiffusion dd{
      p.diffusion == DiffusionModel::None ? 0.0 : p.delta * p.h * p.c0,
      p.diffusion == DiffusionModel::Fourtakas ? p.rho0 / (p.c0 * p.c0) : 0.0};
  const Vec<D> g = p.gravity.template head<D>();
  const std::size_t n = ps.size();
  Reference ref;
  ref.drho.assign(n, 0.0);
  ref.ace.assign(n, Eigen::Vector3d::Zero());
  const double s2 = kernel.support() * kernel.support();
  for (std::size_t a = 0; a < n; ++a) {
    const bool fa = ps.role[a] == Role::Fluid;
    const double rho_a = ps.rho[a], prs_a = eos.pressure(rho_a) / (rho_a * rho_a);
    double drho = 0.0;
    Vec<D> acc = Vec<D>::Zero();
    for (std::size_t b = 0; b < n; ++b) {
      const bool fb = ps.role[b] == Role::Fluid;
      if (!fa && !fb) continue;
      const Vec<D> rab = ps.pos[a] - ps.pos[b];
      const double r2 = rab.squaredNorm();
      if (r2 >= s2 || r2 <= 1e-18) continue;
      const Vec<D> gradw = rab * kernel.f(std::sqrt(r2));
      const Vec<D> vab = ps.velocity(a) - ps.velocity(b);
      const double rho_b = ps.rho[b], m_b = ps.mass[b];
      drho += m_b * vab.dot(gradw);
      double pterm = prs_a + eos.pressure(rho_b) / (rho_b * rho_b);
      const double vr = vab.dot(rab);
      const double inv_r2e = 1.0 / (r2 + p.eta2());
      if (p.viscosity == ViscosityModel::Artificial)
        pterm +=
            av.pi(av.mu(vr, inv_r2e), eos.sound_speed(rho_a), eos.sound_speed(rho_b), rho_a, rho_b);
      else
        acc += lam.factor(m_b, rab.dot(gradw), rho_a, rho_b, inv_r2e) * vab;
      acc -= m_b * pterm * gradw;
      if (fa && vr < 0.0) ref.visc_dt_max = std::max(ref.visc_dt_max, -p.h * vr / (r2 + p.eta2()));
      if (fa && fb)
        drho += dd.term(1.0, dd.weight(true), dd.drho(rho_a, rho_b, g.dot(rab)), rab.dot(gradw),
                        inv_r2e, m_b / rho_b);
    }
    if (fa) acc += g;
    ref.drho[a] = drho;
    ref.ace[a].template head<D>() = acc;
  }
  return ref;
}

template <int D>
void compare(KernelType kt, ViscosityModel visc, DiffusionModel diff, double gamma = 7.0) {
  const double dp = 0.01;
  const int n_side = D == 2 ? 30 : 11;
  ParticleSet<D> ps = random_particles<D>(n_side, dp, 11u + static_cast<unsigned>(kt));
  SolverParams p;
  p.dp = dp;
  p.h = 1.2 * std::sqrt(double(D)) * dp;
  p.kernel = kt;
  p.c0 = 25.0;
  p.alpha = 0.1;
  p.nu = 1e-3;
  p.viscosity = visc;
  p.diffusion = diff;
  p.gamma = gamma;
  p.gravity = D == 2 ? Eigen::Vector3d(0.0, -9.81, 0.0) : Eigen::Vector3d(0.0, 0.0, -9.81);
  const double support = kernel_support_factor(kt) * p.h;
  CellGrid<D> grid(Vec<D>::Constant(-3.0 * dp), Vec<D>::Constant((n_side + 3.0) * dp), support);
  grid.sort(ps);
  ASSERT_EQ(ps.size(), ps.total());
  const TaitEos eos(p.rho0, p.c0, p.gamma);
  ForceBuffers<D> f;
  f.resize(ps.total());
  compute_forces<D, WallsSeeFluid>(ps, grid, p, eos, f);
  const Reference ref =
      with_kernel<D>(kt, p.h, [&](const auto& kernel) { return brute_force<D>(ps, kernel, p); });
  {
    double drho_scale = 0.0, ace_scale = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      drho_scale = std::max(drho_scale, std::abs(ref.drho[i]));
      ace_scale = std::max(ace_scale, ref.ace[i].norm());
    }
    ASSERT_GT(drho_scale, 0.0);
    ASSERT_GT(ace_scale, 0.0);
    // The loop's arithmetic is PairReal (float unless the double-state build): its rounding is
    // bounded per particle (verify/pair_rounding.hpp); 1e-11 of the scale covers double's.
    const PairRounding bound = pair_rounding<D>(ps, p);
    int walls_with_load = 0;
    double worst = 0.0;  // the largest error as a fraction of its bound (reported)
    for (std::size_t i = 0; i < ps.size(); ++i) {
      ASSERT_NEAR(f.drho[i], ref.drho[i], 1e-11 * drho_scale + bound.drho[i]) << "particle " << i;
      worst = std::max(worst, std::abs(f.drho[i] - ref.drho[i]) / (bound.drho[i] + 1e-300));
      for (int d = 0; d < D; ++d) {
        ASSERT_NEAR(f.ace[i][d], ref.ace[i][d], 1e-11 * ace_scale + bound.acc[i])
            << "particle " << i << " axis " << d;
        worst = std::max(worst, std::abs(f.ace[i][d] - ref.ace[i][d]) / (bound.acc[i] + 1e-300));
      }
      walls_with_load += ps.role[i] == Role::FixedWall && ref.ace[i].norm() > 0.0;
    }
    std::cout << "  largest error / rounding bound: " << worst << "\n";
    EXPECT_GT(walls_with_load, 10);  // the wall branch was exercised
    EXPECT_NEAR(f.visc_dt_max, ref.visc_dt_max, 1e-12 * ref.visc_dt_max + bound.visc);
    // cs_max is the largest c0 (rho/rho0)^((gamma-1)/2).
    double rho_max = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) rho_max = std::max(rho_max, double(ps.rho[i]));
    EXPECT_DOUBLE_EQ(f.cs_max, eos.sound_speed(rho_max));
  }
}

class PairLoop
    : public ::testing::TestWithParam<std::tuple<KernelType, ViscosityModel, DiffusionModel>> {};

TEST_P(PairLoop, MatchesBruteForce2D) {
  compare<2>(std::get<0>(GetParam()), std::get<1>(GetParam()), std::get<2>(GetParam()));
}
TEST_P(PairLoop, MatchesBruteForce3D) {
  compare<3>(std::get<0>(GetParam()), std::get<1>(GetParam()), std::get<2>(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(
    AllModels, PairLoop,
    ::testing::Values(
        std::make_tuple(KernelType::Wendland, ViscosityModel::Artificial,
                        DiffusionModel::Fourtakas),
        std::make_tuple(KernelType::Wendland, ViscosityModel::Laminar,
                        DiffusionModel::MolteniColagrossi),
        std::make_tuple(KernelType::Cubic, ViscosityModel::Artificial, DiffusionModel::Fourtakas),
        std::make_tuple(KernelType::Cubic, ViscosityModel::Laminar, DiffusionModel::None),
        std::make_tuple(KernelType::Quintic, ViscosityModel::Artificial,
                        DiffusionModel::MolteniColagrossi),
        std::make_tuple(KernelType::Gaussian, ViscosityModel::Artificial,
                        DiffusionModel::Fourtakas),
        std::make_tuple(KernelType::Gaussian, ViscosityModel::Laminar, DiffusionModel::Fourtakas)));

// Each thread gathers for the cells of its static share of the particles
// (CellGrid::thread_cells): the rates are the same bits at 1, 2, 3 and 4 threads, with the
// masses all equal (the one-mass evaluator, detected in compute_pressure) and not.
template <int D>
void same_at_any_thread_count(bool one_mass) {
  const double dp = 0.01;
  const int n_side = D == 2 ? 40 : 13;
  ParticleSet<D> ps = random_particles<D>(n_side, dp, 29u);
  if (one_mass)
    for (auto& m : ps.mass) m = 1000.0 * std::pow(dp, D);
  SolverParams p;
  p.dp = dp;
  p.h = 1.2 * std::sqrt(double(D)) * dp;
  p.c0 = 25.0;
  p.gravity = D == 2 ? Eigen::Vector3d(0.0, -9.81, 0.0) : Eigen::Vector3d(0.0, 0.0, -9.81);
  const double support = kernel_support_factor(p.kernel) * p.h;
  CellGrid<D> grid(Vec<D>::Constant(-3.0 * dp), Vec<D>::Constant((n_side + 3.0) * dp), support);
  grid.sort(ps);
  const TaitEos eos(p.rho0, p.c0, p.gamma);
  const int threads_before = omp_get_max_threads();
  ForceBuffers<D> ref;
  for (int nt = 1; nt <= 4; ++nt) {
    omp_set_num_threads(nt);
    ForceBuffers<D> f;
    f.resize(ps.total());
    compute_forces<D, WallsSeeFluid>(ps, grid, p, eos, f);
    EXPECT_EQ(f.one_mass, one_mass);
    if (nt == 1) {
      ref = std::move(f);
      continue;
    }
    for (std::size_t i = 0; i < ps.size(); ++i) {
      ASSERT_EQ(f.drho[i], ref.drho[i]) << nt << " threads, particle " << i;
      for (int d = 0; d < D; ++d) ASSERT_EQ(f.ace[i][d], ref.ace[i][d]) << nt << " threads";
    }
    EXPECT_EQ(f.visc_dt_max, ref.visc_dt_max);
  }
  omp_set_num_threads(threads_before);
}
TEST(PairLoopThreads, SameBitsAtAnyThreadCount2D) {
  same_at_any_thread_count<2>(false);
  same_at_any_thread_count<2>(true);
}
TEST(PairLoopThreads, SameBitsAtAnyThreadCount3D) {
  same_at_any_thread_count<3>(false);
  same_at_any_thread_count<3>(true);
}

// The loop takes P/rho^2 and c from the EoS buffers, so any Tait exponent gives the brute-force
// result (the first version assumed gamma = 7 and refused others).
TEST(PairLoopEos, AnyTaitExponent2D) {
  compare<2>(KernelType::Wendland, ViscosityModel::Artificial, DiffusionModel::Fourtakas, 5.0);
}
TEST(PairLoopEos, AnyTaitExponent3D) {
  compare<3>(KernelType::Cubic, ViscosityModel::Artificial, DiffusionModel::MolteniColagrossi, 3.0);
}

// The float gather (issue #16) tests a float copy of the positions: with its margin it keeps
// every pair whose double distance is inside the support, even far from the origin where a
// float coordinate is rounded by ~1e-6 m; without the margin some are dropped (so the test can
// fail).
TEST(FloatGather, KeepsEveryPairInsideTheSupport) {
  constexpr int D = 3;
  const double support = 0.01, extent = 200.0;  // a 200 m flume with a 1 cm support
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ang(0.0, 2.0 * std::acos(-1.0)), z(-1.0, 1.0);
  std::uniform_real_distribution<double> rel(-4e-6, 4e-6);
  const Vec<D> origin = Vec<D>::Zero();
  std::vector<Vec<D>> x;
  const Vec<D> xa(extent - 0.3, 0.5 * extent, 0.7 * extent);
  x.push_back(xa);
  for (int i = 0; i < 4000; ++i) {  // candidates on a shell at the support's edge
    const double t = ang(rng), c = z(rng), s = std::sqrt(1.0 - c * c);
    const Vec<D> dir(s * std::cos(t), s * std::sin(t), c);
    x.push_back(xa + support * (1.0 + rel(rng)) * dir);
  }
  std::vector<float> F(x.size() * D);
  for (std::size_t i = 0; i < x.size(); ++i)
    for (int d = 0; d < D; ++d) F[i * D + d] = static_cast<float>(x[i][d] - origin[d]);
  const std::vector<Role> role(x.size(), Role::Fluid);
  const auto gathered = [&](double margin) {
    std::vector<std::uint32_t> nb(x.size() + 32);
    const double s = support + margin;
    const auto k = gather_neighbours<D, WallsSeeFluid>(
        F.data(), role.data(), F.data(), true, static_cast<float>(s * s), 0,
        static_cast<std::uint32_t>(x.size()), nb.data(), 0);
    std::vector<bool> in(x.size(), false);
    for (std::uint32_t j = 0; j < k; ++j) in[nb[j] & ~kWallBit] = true;
    return in;
  };
  const auto count_missed = [&](const std::vector<bool>& in) {
    int missed = 0;
    for (std::size_t b = 1; b < x.size(); ++b) missed += (x[b] - xa).norm() < support && !in[b];
    return missed;
  };
  int inside = 0;
  for (std::size_t b = 1; b < x.size(); ++b) inside += (x[b] - xa).norm() < support;
  ASSERT_GT(inside, 1000);
  EXPECT_EQ(count_missed(gathered(float_gather_margin(D, extent, support))), 0);
  EXPECT_GT(count_missed(gathered(0.0)), 0);  // the plain float test would drop pairs
}

}  // namespace
}  // namespace swell
