// Periodic boundaries (solver/neighbours/cell_grid.hpp): particles that cross a periodic face
// come back through the other one, and every particle sees, through the periodic images, the
// neighbourhood it would have in an infinite lattice. Checked at the grid (images, wrap,
// kernel sums), in the solver (a uniform stream through a fully periodic box stays uniform;
// momentum of a perturbed periodic block is conserved to round-off), and from the case file
// (the keys, their errors, and a bitwise restart of a periodic channel).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <set>
#include <sstream>

#include "bc/dbc.hpp"
#include "io/case_file.hpp"
#include "io/hdf5_file.hpp"
#include "solver/diagnostics.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/time/simulation.hpp"
#include "tests/case_run.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

// An n^D lattice filling [0, n dp)^D.
template <int D>
ParticleSet<D> lattice(int n, double dp, double rho0, const Vec<D>& v = Vec<D>::Zero()) {
  ParticleSet<D> ps;
  const int nz = D == 3 ? n : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Vec<D> x;
        x[0] = (i + 0.5) * dp;
        x[1] = (j + 0.5) * dp;
        if constexpr (D == 3) x[2] = (k + 0.5) * dp;
        ps.add(x, v, rho0, rho0 * std::pow(dp, D), Role::Fluid, 0);
      }
  return ps;
}

// Kernel sum sum_b W(|x_a - x_b|) of every active particle over its candidates.
template <int D>
std::vector<double> kernel_sums(const ParticleSet<D>& ps, const CellGrid<D>& grid,
                                const WendlandC2<D>& w) {
  std::vector<double> s(ps.size(), 0.0);
  for (std::size_t a = 0; a < ps.size(); ++a)
    grid.for_each_candidate(a, [&](std::uint32_t b) {
      const double r = (ps.pos[a] - ps.pos[b]).norm();
      if (r < w.support()) s[a] += w.w(r);
    });
  return s;
}

template <int D>
void check_images(std::array<bool, D> axes) {
  const int n = D == 2 ? 16 : 8;
  const double dp = 0.1, h = 1.3 * dp, L = n * dp;
  const WendlandC2<D> w(h);
  CellGrid<D> grid(Vec<D>::Zero(), Vec<D>::Constant(L), w.support());
  grid.set_periodic(axes);
  ParticleSet<D> ps = lattice<D>(n, dp, 1000.0);
  const std::size_t total = ps.total();
  grid.sort(ps);
  EXPECT_GT(ps.n_ghost, 0u);
  EXPECT_EQ(ps.total(), total);
  EXPECT_EQ(ps.stored(), total + ps.n_ghost);
  // Images lie outside the domain by less than one support, on the periodic axes only.
  for (std::size_t k = ps.ghost_begin(); k < ps.stored(); ++k)
    for (int d = 0; d < D; ++d) {
      if (!axes[d]) {
        EXPECT_TRUE(ps.pos[k][d] > 0.0 && ps.pos[k][d] < L);
        continue;
      }
      EXPECT_GT(ps.pos[k][d], -w.support());
      EXPECT_LT(ps.pos[k][d], L + w.support());
    }
  // On a fully periodic lattice every particle has the interior kernel sum (an infinite
  // lattice); on a partly periodic one, every particle has the sum of the particle at the
  // same place along the non-periodic axes.
  const std::vector<double> s = kernel_sums<D>(ps, grid, w);
  const double interior = [&] {
    for (std::size_t a = 0; a < ps.size(); ++a)
      if ((ps.pos[a].array() > 0.3 * L).all() && (ps.pos[a].array() < 0.7 * L).all()) return s[a];
    return 0.0;
  }();
  for (std::size_t a = 0; a < ps.size(); ++a) {
    bool interior_along_open = true;
    for (int d = 0; d < D; ++d)
      interior_along_open =
          interior_along_open && (axes[d] || (ps.pos[a][d] > 0.3 * L && ps.pos[a][d] < 0.7 * L));
    if (interior_along_open) EXPECT_NEAR(s[a], interior, 1e-12 * interior) << "a=" << a;
  }
  // Without the images a particle at a periodic face misses part of its neighbourhood.
  grid.drop_ghosts(ps);
  EXPECT_EQ(ps.n_ghost, 0u);
  EXPECT_EQ(ps.stored(), total);
  EXPECT_EQ(grid.ghost_count(), 0u);
  const std::vector<double> cut = kernel_sums<D>(ps, grid, w);
  EXPECT_LT(*std::min_element(cut.begin(), cut.end()), 0.8 * interior);
}

TEST(PeriodicGrid, ImagesCompleteTheNeighbourhood2D) {
  check_images<2>({true, true});
  check_images<2>({true, false});
  check_images<2>({false, true});
}

TEST(PeriodicGrid, ImagesCompleteTheNeighbourhood3D) {
  check_images<3>({true, true, true});
  check_images<3>({false, true, false});
}

TEST(PeriodicGrid, WrapsCrossingParticles) {
  const double dp = 0.1, L = 1.6;
  CellGrid<2> grid(Vec<2>::Zero(), Vec<2>::Constant(L), 0.26);
  grid.set_periodic({true, false});
  ParticleSet<2> ps = lattice<2>(16, dp, 1000.0);
  ps.pos[0] = Vec<2>(L + 0.01, 0.55);  // crossed x = max
  ps.pos_prev[0] = Vec<2>(L - 0.01, 0.55);
  ps.pos[1] = Vec<2>(-0.02, 0.65);     // crossed x = min
  ps.pos[2] = Vec<2>(0.75, L + 0.01);  // crossed a face that is not periodic
  const auto r = grid.sort(ps);
  EXPECT_EQ(r.out_of_domain, 1u);
  ASSERT_EQ(ps.size(), 16u * 16u - 1u);
  bool seen0 = false, seen1 = false;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.id[i] == 0) {
      seen0 = true;
      EXPECT_NEAR(ps.pos[i].x(), 0.01, 1e-12);
      EXPECT_NEAR(ps.pos_prev[i].x(), -0.01, 1e-12);  // the displacement is kept
    }
    if (ps.id[i] == 1) {
      seen1 = true;
      EXPECT_NEAR(ps.pos[i].x(), L - 0.02, 1e-12);
    }
  }
  EXPECT_TRUE(seen0 && seen1);
}

TEST(PeriodicGrid, RefusesAPeriodShorterThanTwoSupports) {
  CellGrid<2> grid(Vec<2>::Zero(), Vec<2>(0.5, 2.0), 0.3);
  EXPECT_THROW(grid.set_periodic({true, false}), std::invalid_argument);
  EXPECT_NO_THROW(grid.set_periodic({false, true}));
}

template <int D>
SolverParams periodic_params(int n, double dp) {
  SolverParams p;
  p.dp = dp;
  p.h = 1.3 * dp;
  p.gravity.setZero();
  p.c0 = 20.0;
  p.alpha = 0.1;
  p.domain_min = Eigen::Vector3d::Zero();
  p.domain_max = Eigen::Vector3d::Constant(n * dp);
  for (int d = 0; d < D; ++d) p.periodic[d] = true;
  return p;
}

template <int D>
void check_uniform_stream(IntegratorType integ) {
  const int n = D == 2 ? 20 : 8;
  const double dp = 0.01;
  Vec<D> u = Vec<D>::Zero();
  // Fast (Mach 0.15) so every particle crosses the box in a few hundred steps: a compressed
  // lattice is itself unstable to perturbations (measured here: round-off seeded by the
  // motion grows ~6x per 500 steps at rest and in motion alike), which a long run would show.
  u[0] = 3.0;
  u[1] = -2.0;
  SolverParams p = periodic_params<D>(n, dp);
  p.integrator = integ;
  // Compressed by 1 %: a uniform positive pressure, which pulls a lattice with a free
  // boundary apart at once. With the images the periodic lattice is an exact equilibrium.
  const double rho = 1010.0;
  Simulation<D> sim(p, lattice<D>(n, dp, rho, u), make_dbc<D>());
  // Until every particle crossed the box along x at least once.
  while (sim.time() < 1.2 * n * dp / u[0]) sim.step();
  const ParticleSet<D>& ps = sim.particles();
  EXPECT_EQ(ps.n_ghost, 0u);  // none between steps
  EXPECT_EQ(sim.excluded().total(), 0u);
  ASSERT_EQ(ps.size(), static_cast<std::size_t>(std::pow(n, D)));
  std::set<std::uint32_t> ids(ps.id.begin(), ps.id.begin() + ps.size());
  EXPECT_EQ(ids.size(), ps.size());
  double dv = 0.0, drho = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    dv = std::max(dv, (ps.vel[i] - u).norm());
    drho = std::max(drho, std::abs(ps.rho[i] / rho - 1.0));
    for (int d = 0; d < D; ++d) {
      EXPECT_GE(ps.pos[i][d], -0.5 * u.norm() * sim.dt());
      EXPECT_LE(ps.pos[i][d], n * dp + 0.5 * u.norm() * sim.dt());
    }
  }
  std::cout << "  " << D << "D uniform stream after " << sim.steps()
            << " steps: max |v - u| = " << dv << ", max |rho/rho_initial - 1| = " << drho << "\n";
  EXPECT_LT(dv, 1e-9);
  EXPECT_LT(drho, 1e-12);
}

TEST(PeriodicRun, UniformStreamStaysUniform2D) {
  check_uniform_stream<2>(IntegratorType::Symplectic);
  check_uniform_stream<2>(IntegratorType::Verlet);
}

TEST(PeriodicRun, UniformStreamStaysUniform3D) {
  check_uniform_stream<3>(IntegratorType::Symplectic);
}

TEST(PeriodicRun, PerturbedBlockConservesMomentum) {
  const int n = 24;
  const double dp = 0.01;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  ParticleSet<2> ps;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec<2> x((i + 0.5 + 0.05 * r(rng)) * dp, (j + 0.5 + 0.05 * r(rng)) * dp);
      const Vec<2> v(0.5 * r(rng), 0.5 * r(rng));
      ps.add(x, v, 1000.0 * (1.0 + 0.01 * r(rng)), 0.1 * (1.0 + 0.2 * r(rng)), Role::Fluid, 0);
    }
  Simulation<2> sim(periodic_params<2>(n, dp), ps, make_dbc<2>());
  const auto before = fluid_totals(sim.particles());
  double scale = 0.0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    scale += sim.particles().mass[i] * sim.particles().vel[i].norm();
  for (int s = 0; s < 200; ++s) sim.step();
  const auto after = fluid_totals(sim.particles());
  EXPECT_EQ(sim.excluded().total(), 0u);
  EXPECT_EQ(after.count, before.count);
  const double drift = (after.momentum - before.momentum).norm();
  std::cout << "  periodic momentum drift over 200 steps: " << drift / scale << " of sum m|v|\n";
  EXPECT_LT(drift, 1e-12 * scale);
}

// A channel periodic along x (walls above and below, its x faces open), water between,
// driven by a gravity component along x.
std::string channel_case(double t_end, const std::string& periodic = "[x]") {
  std::ostringstream s;
  s << "name: periodic_channel\ndim: 2\ndp: 0.01\n"
    << "time: {end: " << t_end << "}\n"
    << "physics: {gravity: [0.2, -9.81], viscosity: {model: laminar, nu: 1.0e-3}}\n"
    << "domain: {min: [0, -0.05], max: [0.12, 0.15], periodic: " << periodic << "}\n"
    << "bodies:\n"
    << "  - {name: channel, kind: boundary, shape: {box: {min: [0, 0], max: [0.12, 0.1]}}, "
       "layers: 3, open: [xmin, xmax]}\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.12, 0.1]}}}\n"
    << "output: {every: 0.01, vtk: false, hdf5: true}\n";
  return s.str();
}

TEST(PeriodicCase, KeysAndErrors) {
  const CaseSpec spec = parse_case_text(channel_case(0.1), "channel.yaml");
  EXPECT_TRUE(spec.periodic[0]);
  EXPECT_FALSE(spec.periodic[1]);
  auto error_of = [](const std::string& text) {
    try {
      parse_case_text(text, "channel.yaml");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of(channel_case(0.1, "[z]")).find("does not exist in a 2D case"),
            std::string::npos);
  EXPECT_NE(error_of(channel_case(0.1, "[x, x]")).find("listed twice"), std::string::npos);
  EXPECT_NE(error_of(channel_case(0.1, "[w]")).find("periodic"), std::string::npos);
  EXPECT_NE(error_of(channel_case(0.1, "x")).find("a list of axes"), std::string::npos);
}

TEST(PeriodicCase, ChannelRestartsBitwise) {
  const fs::path a = fs::temp_directory_path() / "swell_test_periodic_a";
  const fs::path b = fs::temp_directory_path() / "swell_test_periodic_b";
  const auto [ca, cb] =
      test::split_run<2>(channel_case(0.06), channel_case(0.03), "periodic_channel.yaml", a, b);
  EXPECT_EQ(ca.clock.steps, cb.clock.steps);
  EXPECT_GT(ca.clock.steps, 50);
  ASSERT_EQ(ca.particles.total(), cb.particles.total());
  EXPECT_EQ(ca.particles.id, cb.particles.id);
  EXPECT_EQ(ca.particles.rho, cb.particles.rho);
  EXPECT_EQ(ca.particles.pos, cb.particles.pos);
  EXPECT_EQ(ca.particles.vel, cb.particles.vel);
  // Nothing left the domain, and the water moved along x.
  EXPECT_EQ(ca.clock.excluded.out_of_domain, 0u);
  double mean_u = 0.0;
  std::size_t nf = 0;
  for (std::size_t i = 0; i < ca.particles.size(); ++i)
    if (is_fluid(ca.particles.role[i])) mean_u += ca.particles.vel[i].x(), ++nf;
  EXPECT_GT(mean_u / nf, 0.0);
}

}  // namespace
}  // namespace swell
