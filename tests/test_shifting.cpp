// Particle shifting (solver/physics/shifting.hpp, the ShiftingHook): the operator on hand-made
// particle sets (a perfect lattice does not move; a disordered one becomes regular while its
// free surface stays where it is: the normal part is removed there), the case keys, and whole
// runs: a still tank does not drift, the dam-break front stays where it was without shifting
// (and within the Martin & Moyce tolerance) while the particle distribution becomes more
// regular, and a restart continues bitwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>
#include <sstream>

#include "case/reader.hpp"
#include "case/setup.hpp"
#include "io/hdf5_file.hpp"
#include "solver/diagnostics.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/physics/shifting.hpp"
#include "solver/time/shifting_hook.hpp"
#include "tests/case_run.hpp"
#include "tests/state_precision.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

constexpr double kDp = 0.01;
constexpr double kRho0 = 1000.0;

// nx x ny fluid lattice at (i + 1/2, j + 1/2) dp, each displaced by up to `jitter` dp at random,
// all moving at speed u along x.
ParticleSet<2> block(int nx, int ny, double jitter, double u, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-jitter * kDp, jitter * kDp);
  ParticleSet<2> ps;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      Vec<2> x((i + 0.5) * kDp, (j + 0.5) * kDp);
      if (jitter > 0.0) x += Vec<2>(d(rng), d(rng));
      ps.add(x, Vec<2>(u, 0.0), kRho0, kRho0 * kDp * kDp, Role::Fluid, 0);
    }
  return ps;
}

struct Fixture {
  WendlandC2<2> kernel{std::sqrt(2.0) * kDp};
  CellGrid<2> grid{Vec<2>(-0.1, -0.1), Vec<2>(0.5, 0.5), kernel.support()};
  ShiftingParams params;
};

// Number density sum_b V_b W_ab (1 inside a regular fluid): its spread over the interior
// particles is the disorder shifting removes.
double interior_spread(const ParticleSet<2>& ps, const CellGrid<2>& grid, const WendlandC2<2>& k,
                       double x0, double x1, double y0, double y1) {
  double s = 0.0, s2 = 0.0;
  int n = 0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const Vec<2>& x = ps.pos[a];
    if (x.x() < x0 || x.x() > x1 || x.y() < y0 || x.y() > y1) continue;
    double c = 0.0;
    grid.for_each_candidate(
        a, [&](std::uint32_t b) { c += ps.mass[b] / ps.rho[b] * k.w((x - ps.pos[b]).norm()); });
    s += c;
    s2 += c * c;
    ++n;
  }
  const double mean = s / n;
  return std::sqrt(std::max(0.0, s2 / n - mean * mean)) / mean;
}

TEST(ShiftingOperator, PerfectLatticeInteriorStaysAndSurfaceIsFound) {
  Fixture f;
  ParticleSet<2> ps = block(30, 30, 0.0, 1.0);
  f.grid.sort(ps);
  ShiftingWork<2> work;
  const auto& shift = work.shift;
  const double dt = 1e-4;
  const ShiftingStats st = compute_shifting<2>(ps, f.grid, f.kernel, f.params, kDp, dt, work);
  const double w_dp = f.kernel.w(kDp);
  double interior_max = 0.0, top_normal_max = 0.0, div_in_lo = 9.0, div_in_hi = 0.0;
  double div_top_hi = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const Vec<2>& x = ps.pos[a];
    const auto t = shifting_terms<2>(ps, f.grid, f.kernel, w_dp, f.params.tensile_r, a);
    const bool interior = x.x() > 0.05 && x.x() < 0.25 && x.y() > 0.05 && x.y() < 0.25;
    if (interior) {
      interior_max = std::max(interior_max, shift[a].norm());
      div_in_lo = std::min(div_in_lo, t.div_r);
      div_in_hi = std::max(div_in_hi, t.div_r);
    }
    if (x.y() > 0.29 && x.x() > 0.05 && x.x() < 0.25) {  // top row, away from the sides
      div_top_hi = std::max(div_top_hi, t.div_r);
      top_normal_max = std::max(top_normal_max, std::abs(shift[a].y()));
    }
  }
  std::cout << "  lattice: interior div r in [" << div_in_lo << ", " << div_in_hi
            << "], top row div r <= " << div_top_hi << "; " << st.surface << " of " << ps.size()
            << " particles at the surface\n";
  EXPECT_LT(interior_max, 1e-12 * kDp);  // grad C = 0 inside a perfect lattice
  EXPECT_NEAR(div_in_lo, 2.0, 0.05);
  EXPECT_NEAR(div_in_hi, 2.0, 0.05);
  EXPECT_LT(div_top_hi, ShiftingParams::default_threshold(2));
  EXPECT_LT(top_normal_max, 1e-12 * kDp);  // no push out through the surface
  // The outer rows (2 per side at h = 1.41 dp) and nothing deeper are surface particles.
  EXPECT_GE(st.surface, 4u * 29u);
  EXPECT_LE(st.surface, 4u * 2u * 30u);
}

// A block with 20 % random displacements, shifted again and again at a fixed |v| dt: its
// interior becomes regular (the spread of the number density falls), while the free surface
// stays put: the mean height of the top particles moves by less than 0.05 dp. Without the
// normal's removal the surface rows would be pushed outwards at every pass.
TEST(ShiftingOperator, DisorderedBlockRelaxesAndKeepsItsSurface) {
  Fixture f;
  ParticleSet<2> ps = block(30, 30, 0.2, 1.0);
  ShiftingWork<2> work;
  const auto& shift = work.shift;
  auto top_height = [&] {
    std::vector<double> ys;
    for (std::size_t a = 0; a < ps.size(); ++a)
      if (ps.pos[a].x() > 0.05 && ps.pos[a].x() < 0.25) ys.push_back(ps.pos[a].y());
    std::sort(ys.begin(), ys.end());
    double s = 0.0;
    const std::size_t k = 20;  // ~ the top row of this central strip
    for (std::size_t i = ys.size() - k; i < ys.size(); ++i) s += ys[i];
    return s / k;
  };
  f.grid.sort(ps);
  const double spread0 = interior_spread(ps, f.grid, f.kernel, 0.06, 0.24, 0.06, 0.24);
  const double top0 = top_height();
  // |v| dt = 0.02 dp per pass: D = 2 h |v| dt ~ 0.04 h dp.
  const double dt = 0.02 * kDp / 1.0;
  double max_shift = 0.0;
  for (int pass = 0; pass < 300; ++pass) {
    f.grid.sort(ps);
    const ShiftingStats st = compute_shifting<2>(ps, f.grid, f.kernel, f.params, kDp, dt, work);
    max_shift = std::max(max_shift, st.max_shift);
    for (std::size_t a = 0; a < ps.size(); ++a) ps.pos[a] += shift[a];
  }
  f.grid.sort(ps);
  const double spread1 = interior_spread(ps, f.grid, f.kernel, 0.06, 0.24, 0.06, 0.24);
  const double top1 = top_height();
  std::cout << "  disordered block: interior number-density spread " << 100 * spread0 << " % -> "
            << 100 * spread1 << " %; top surface moved " << (top1 - top0) / kDp
            << " dp; largest shift " << max_shift / kDp << " dp per pass\n";
  EXPECT_LT(spread1, 0.5 * spread0);
  EXPECT_LT(std::abs(top1 - top0), 0.05 * kDp);
  EXPECT_LT(max_shift, 0.1 * kDp);
}

// The SIMD pass (ShiftingEvaluator in the pair driver) gives the sums of the plain loop.
TEST(ShiftingOperator, PairDriverPassEqualsThePlainSums) {
  Fixture f;
  ParticleSet<2> ps = block(20, 20, 0.2, 1.0);
  f.grid.sort(ps);
  ShiftingWork<2> work;
  (void)compute_shifting<2>(ps, f.grid, f.kernel, f.params, kDp, 1e-4, work);
  const double w_dp = f.kernel.w(kDp);
  double worst = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const auto t = shifting_terms<2>(ps, f.grid, f.kernel, w_dp, f.params.tensile_r, a);
    worst = std::max(worst, (work.grad_c[a] - t.grad_c).norm() * kDp);
    worst = std::max(worst, std::abs(work.div_r[a] - t.div_r));
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(ShiftingOperator, ParticlesAtRestAreNotShifted) {
  Fixture f;
  ParticleSet<2> ps = block(20, 20, 0.2, 0.0);
  f.grid.sort(ps);
  ShiftingWork<2> work;
  const ShiftingStats st = compute_shifting<2>(ps, f.grid, f.kernel, f.params, kDp, 1e-3, work);
  EXPECT_EQ(st.shifted, 0u);  // Skillen et al.'s D = A h |v| dt vanishes
}

// The modes near walls (DualSPHysics' ShiftMode): a disordered block resting on a fixed floor
// and beside a moving wall. full shifts every moving fluid particle; nobound leaves exactly the
// fluid particles with a wall particle within the kernel support where they are (and no other);
// nofixed only those near the fixed floor.
TEST(ShiftingOperator, ModesLeaveExactlyTheParticlesNearTheExcludedWalls) {
  Fixture f;
  ParticleSet<2> ps = block(20, 20, 0.2, 1.0);
  for (int layer = 0; layer < 3; ++layer)  // a fixed floor under the block
    for (int i = -3; i < 23; ++i)
      ps.add(Vec<2>((i + 0.5) * kDp, -(layer + 0.5) * kDp), Vec<2>::Zero(), kRho0,
             kRho0 * kDp * kDp, Role::FixedWall, 1);
  for (int layer = 0; layer < 3; ++layer)  // a moving wall on its left
    for (int j = 0; j < 20; ++j)
      ps.add(Vec<2>(-(layer + 0.5) * kDp, (j + 0.5) * kDp), Vec<2>::Zero(), kRho0,
             kRho0 * kDp * kDp, Role::MovingWall, 2);
  f.grid.sort(ps);
  const double support2 = f.kernel.support() * f.kernel.support();
  std::vector<int> near_fixed(ps.size(), 0), near_moving(ps.size(), 0);
  for (std::size_t a = 0; a < ps.size(); ++a)
    for (std::size_t b = 0; b < ps.size(); ++b)
      if ((ps.pos[a] - ps.pos[b]).squaredNorm() < support2) {
        near_fixed[a] |= ps.role[b] == Role::FixedWall;
        near_moving[a] |= ps.role[b] == Role::MovingWall;
      }
  const double dt = 1e-4;
  ShiftingWork<2> full, nobound, nofixed;
  const ShiftingStats s_full = compute_shifting<2>(ps, f.grid, f.kernel, f.params, kDp, dt, full);
  ShiftingParams p = f.params;
  p.mode = ShiftMode::NoBound;
  const ShiftingStats s_nb = compute_shifting<2>(ps, f.grid, f.kernel, p, kDp, dt, nobound);
  p.mode = ShiftMode::NoFixed;
  const ShiftingStats s_nf = compute_shifting<2>(ps, f.grid, f.kernel, p, kDp, dt, nofixed);
  std::size_t n_near_any = 0, n_near_fixed = 0, fluid = 0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.role[a] != Role::Fluid) continue;
    ++fluid;
    const bool any = near_fixed[a] || near_moving[a];
    n_near_any += any;
    n_near_fixed += near_fixed[a] != 0;
    ASSERT_GT(full.shift[a].norm(), 0.0) << a;  // disordered and moving: every one shifts
    if (any)
      EXPECT_EQ(nobound.shift[a].norm(), 0.0) << a;
    else
      EXPECT_GT(nobound.shift[a].norm(), 0.0) << a;
    if (near_fixed[a])
      EXPECT_EQ(nofixed.shift[a].norm(), 0.0) << a;
    else
      EXPECT_GT(nofixed.shift[a].norm(), 0.0) << a;
  }
  std::cout << "  modes: " << fluid << " fluid particles, " << n_near_any << " near a wall, "
            << n_near_fixed << " near the fixed floor\n";
  EXPECT_GT(n_near_fixed, 0u);
  EXPECT_GT(n_near_any, n_near_fixed);
  EXPECT_EQ(s_full.near_wall, 0u);
  EXPECT_EQ(s_nb.near_wall, n_near_any);
  EXPECT_EQ(s_nf.near_wall, n_near_fixed);
}

// correct_density moves each shifted particle's density with it (Lind et al. 2012, section
// 3.3): on a linear density field, rho + dr . grad rho is the field at the new position to
// round-off wherever the kernel-gradient correction holds (a full or one-sided support), while
// without it the density stays the value of the old position.
TEST(ShiftingOperator, DensityCorrectionFollowsALinearField) {
  Fixture f;
  ParticleSet<2> ps = block(24, 24, 0.2, 1.0);
  const Vec<2> grad(40.0, -70.0);  // kg/m^4 (about the hydrostatic gradient rho0 g / c0^2 x 100)
  const auto field = [&](const Vec<2>& x) { return kRho0 + grad.dot(x); };
  // Positions on multiples of 2^-12 m: the field's values are stored exactly in float too.
  for (std::size_t a = 0; a < ps.size(); ++a) {
    for (int d = 0; d < 2; ++d) ps.pos[a][d] = std::round(ps.pos[a][d] * 4096.0) / 4096.0;
    ps.rho[a] = static_cast<StateReal>(field(ps.pos[a]));
    ASSERT_EQ(double(ps.rho[a]), field(ps.pos[a]));
  }
  f.grid.sort(ps);
  ShiftingParams p = f.params;
  p.correct_density = true;
  ShiftingWork<2> work;
  const double dt = 0.05 * kDp;  // |v| dt = 0.05 dp: shifts of a few percent of dp
  (void)compute_shifting<2>(ps, f.grid, f.kernel, p, kDp, dt, work);
  double worst = 0.0, moved = 0.0;
  std::size_t uncorrected = 0;
  const auto near = [&](const Vec<2>& x, auto&& fn) { f.grid.for_each_candidate_near(x, fn); };
  const auto fluid = [&](std::uint32_t) { return true; };
  for (std::size_t a = 0; a < ps.size(); ++a) {
    double det = 0.0;
    (void)kgc_matrix<2>(ps, f.kernel, near, static_cast<std::uint32_t>(a), fluid, 0.1, &det);
    const double want = field(ps.pos[a] + work.shift[a]);
    if (!(std::abs(det) >= 0.1)) {  // a corner's moment matrix: plain gradient, not exact
      ++uncorrected;
      continue;
    }
    worst = std::max(worst, std::abs(ps.rho[a] + work.drho[a] - want));
    moved = std::max(moved, std::abs(ps.rho[a] - want));
  }
  std::cout << "  " << uncorrected << " of " << ps.size()
            << " particles without the gradient correction (|det| < 0.1)\n";
  EXPECT_LT(uncorrected, ps.size() / 20);
  std::cout << "  density correction on a linear field: largest error " << worst
            << " kg/m^3 (uncorrected " << moved << ")\n";
  EXPECT_GT(moved, 1e-2);
  EXPECT_LT(worst, 1e-9 * moved + 1e-10);
}

// ---------------------------------------------------------------------------------------------
// Case keys

TEST(ShiftingCase, KeysAndErrors) {
  const std::string head =
      "name: s\ndim: 2\ndp: 0.01\ntime: {end: 1}\nbodies:\n"
      "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.1, 0.1]}}}\n";
  const CaseSpec def = parse_case_text(head, "s.yaml");
  EXPECT_EQ(def.shifting, ShiftingModel::None);
  const CaseSpec on = parse_case_text(
      head + "physics: {shifting: {model: fickian, coefficient: 3, surface_threshold: 1.2}}\n",
      "s.yaml");
  EXPECT_EQ(on.shifting, ShiftingModel::Fickian);
  EXPECT_EQ(on.shift_coefficient, 3.0);
  EXPECT_EQ(on.shift_surface_threshold, 1.2);
  const struct {
    const char* physics;
    const char* message;
  } bad[] = {
      {"{shifting: {model: lind}}", "physics.shifting.model"},
      {"{shifting: {model: fickian, coefficient: 0}}", "physics.shifting.coefficient"},
      {"{shifting: {model: fickian, coefficient: 50}}", "(0, 10]"},
      {"{shifting: {model: fickian, surface_threshold: 2.5}}", "(0, dim)"},
      {"{shifting: {model: none, coefficient: 2}}", "coefficient"},
      {"{shifting: fickian}", "a map"},
  };
  for (const auto& b : bad) {
    try {
      (void)parse_case_text(head + "physics: " + b.physics + "\n", "s.yaml");
      ADD_FAILURE() << b.physics << " was accepted";
    } catch (const CaseError& e) {
      EXPECT_NE(std::string(e.what()).find(b.message), std::string::npos)
          << b.physics << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("s.yaml:"), std::string::npos) << e.what();
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Runs

std::string shifting_key(bool on) {
  return on ? "physics: {shifting: {model: fickian}}\n" : "";
}

// A still tank keeps still with shifting on: |v| ~ 0 makes the shift vanish, and where the
// settling motion moves particles the surface is not pushed up. Over 5 s the mean height of
// the top fluid row moves by less than 0.1 dp and the largest speed stays as small as
// without shifting.
TEST(ShiftingRun, StillTankDoesNotDrift) {
  for (bool on : {false, true}) {
    std::ostringstream s;
    s << "name: still\ndim: 2\ndp: 0.02\ntime: {end: 5}\n"
      << shifting_key(on)
      << "bodies:\n"
         "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.4, 0.3]}}, "
         "layers: 3, open: [ymax]}\n"
         "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.4, 0.2]}}}\n";
    CaseSetup<2> setup = setup_case<2>(parse_case_text(s.str(), "still.yaml"));
    Simulation<2> sim = make_simulation<2>(setup, std::move(setup.particles));
    auto top_row = [&] {
      const auto& ps = sim.particles();
      double top = -1.0;
      for (std::size_t i = 0; i < ps.size(); ++i)
        if (ps.role[i] == Role::Fluid) top = std::max(top, ps.pos[i].y());
      double sum = 0.0;
      int n = 0;
      for (std::size_t i = 0; i < ps.size(); ++i)
        if (ps.role[i] == Role::Fluid && ps.pos[i].y() > top - 0.5 * 0.02)
          sum += ps.pos[i].y(), ++n;
      return sum / n;
    };
    const double top0 = top_row();
    double vmax = 0.0;
    while (sim.time() < 5.0) {
      sim.step();
      if (sim.time() < 2.0) continue;  // the first seconds settle the initial lattice
      const auto& ps = sim.particles();
      for (std::size_t i = 0; i < ps.size(); ++i)
        if (ps.role[i] == Role::Fluid) vmax = std::max(vmax, ps.velocity(i).norm());
    }
    const double drift = (top_row() - top0) / 0.02;
    std::cout << "  still tank, shifting " << (on ? "on" : "off") << ": top row moved " << drift
              << " dp in 5 s; largest speed over t = 2-5 s " << vmax << " m/s\n";
    EXPECT_EQ(sim.excluded().total(), 0u);
    EXPECT_LT(std::abs(drift), 0.1);
    EXPECT_LT(vmax, 0.02);
  }
}

std::string dambreak(double t_end, bool on) {
  std::ostringstream s;
  s << "name: shift_db\ndim: 2\ndp: 0.0028575\ntime: {end: " << t_end << "}\n"
    << shifting_key(on) << "bodies:\n"
    << "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.28575, 0.2286]}}, "
       "layers: 3, open: [ymax]}\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.05715, 0.1143]}}}\n"
    << "output: {every: 0.01, vtk: false, hdf5: true}\n";
  return s.str();
}

// Clumping: the fraction of fluid particles whose nearest other particle (fluid or wall) is
// closer than 0.7 dp. A regular distribution has none; SPH without shifting lets particles
// pair up in compressed, sheared flow.
double clumped_fraction(const Simulation<2>& sim, double dp) {
  const auto& ps = sim.particles();
  std::size_t fluid = 0, close = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.role[i] != Role::Fluid) continue;
    double d2 = 1e30;
    for (std::size_t j = 0; j < ps.size(); ++j)
      if (j != i) d2 = std::min(d2, (ps.pos[i] - ps.pos[j]).squaredNorm());
    ++fluid;
    close += d2 < 0.49 * dp * dp;
  }
  return static_cast<double>(close) / static_cast<double>(fluid);
}

// The Martin & Moyce column at a/dp = 20: the surge front with shifting stays within 3 % of
// the front without it at T = 2, 2.5, 3, and the particles clump less (clumped_fraction, at
// t = 0.25 s when the surge hits the far wall and at t = 0.5 s after the run-up has fallen).
TEST(ShiftingRun, DamBreakFrontAndRegularity) {
  constexpr double a = 0.05715, g = 9.81;
  double fronts[2][3] = {};
  double spread[2][2] = {};
  for (int on = 0; on < 2; ++on) {
    CaseSetup<2> setup = setup_case<2>(parse_case_text(dambreak(0.25, on), "db.yaml"));
    const double floor = setup.floor, band = 2.0 * setup.params.h, dp = setup.params.dp;
    Simulation<2> sim = make_simulation<2>(setup, std::move(setup.particles));
    const double t_scale = std::sqrt(2.0 * g / a);
    std::vector<std::pair<double, double>> front;
    bool leaked = false;
    while (sim.time() < 0.25) {
      sim.step();
      const auto& ps = sim.particles();
      front.emplace_back(sim.time() * t_scale, surge_front(ps, Vec<2>(0, 1), floor, band, dp) / a);
      for (std::size_t i = 0; i < ps.size(); ++i)
        if (ps.role[i] == Role::Fluid &&
            (ps.pos[i].x() < 0 || ps.pos[i].x() > 5 * a || ps.pos[i].y() < 0))
          leaked = true;
    }
    EXPECT_FALSE(leaked) << "shifting " << on;
    EXPECT_EQ(sim.excluded().total(), 0u);
    const double checks[3] = {2.0, 2.5, 3.0};
    for (int k = 0; k < 3; ++k)
      for (std::size_t i = 0; i + 1 < front.size(); ++i)
        if (front[i].first <= checks[k] && front[i + 1].first > checks[k])
          fronts[on][k] = front[i].second;
    spread[on][0] = clumped_fraction(sim, dp);
    while (sim.time() < 0.5) sim.step();
    EXPECT_EQ(sim.excluded().total(), 0u);
    spread[on][1] = clumped_fraction(sim, dp);
  }
  std::cout << "  dam break a/dp = 20, front Z at T = 2, 2.5, 3: without shifting " << fronts[0][0]
            << ", " << fronts[0][1] << ", " << fronts[0][2] << "; with " << fronts[1][0] << ", "
            << fronts[1][1] << ", " << fronts[1][2]
            << ". Fluid particles with a neighbour closer than 0.7 dp, without -> with shifting: "
               "t = 0.25 s "
            << 100 * spread[0][0] << " % -> " << 100 * spread[1][0] << " %, t = 0.5 s "
            << 100 * spread[0][1] << " % -> " << 100 * spread[1][1] << " %\n";
  for (int k = 0; k < 3; ++k) {
    ASSERT_GT(fronts[0][k], 0.0);
    EXPECT_LT(std::abs(fronts[1][k] / fronts[0][k] - 1.0), 0.03) << "check " << k;
  }
  EXPECT_LT(spread[1][0], 0.75 * spread[0][0]);
  EXPECT_LT(spread[1][1], 0.75 * spread[0][1]);
}

TEST(ShiftingRun, RestartContinuesBitwise) {
  const auto [ca, cb] = test::split_run<2>(dambreak(0.04, true), dambreak(0.02, true), "db.yaml",
                                           fs::temp_directory_path() / "swell_shift_full",
                                           fs::temp_directory_path() / "swell_shift_split");
  EXPECT_EQ(ca.clock.steps, cb.clock.steps);
  EXPECT_GT(ca.clock.steps, 100);
  EXPECT_EQ(ca.particles.pos, cb.particles.pos);
  EXPECT_EQ(ca.particles.vel, cb.particles.vel);
  EXPECT_EQ(ca.particles.rho, cb.particles.rho);
}

}  // namespace
}  // namespace swell
