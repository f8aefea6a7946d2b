// Moving boundary bodies (bc/moving_bodies.hpp with the laws of bc/motion.hpp) against theory:
//  - a closed box full of water accelerated at a: the mean pressure difference between its rear
//    and front walls is rho a L on top of hydrostatics; mass exactly constant; no particle
//    crosses a moving wall (2D and 3D);
//  - an open tank under the same acceleration: the mean free-surface slope over one sloshing
//    period is a/g;
//  - Stokes' first problem: a plate started impulsively under laminar viscosity drags the
//    fluid above it as U erfc(y / (2 sqrt(nu t)));
//  - a tank swayed for one period at small amplitude, then released: the fluid sloshes at the
//    first mode's frequency of linear theory, omega^2 = g k tanh(k H), k = pi / L.
// Each test runs the real case path (case text -> setup_case -> make_simulation).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "case/reader.hpp"
#include "run/run.hpp"
#include "solver/diagnostics.hpp"
#include "solver/gauges.hpp"
#include "tests/state_precision.hpp"

namespace swell {
namespace {

constexpr double kG = 9.81, kRho0 = 1000.0;

template <int D>
CaseSetup<D> setup_from(const std::string& text) {
  return setup_case<D>(parse_case_text(text, "moving_case.yaml"));
}

// Displacement of a body with `type: linear, acceleration: [a, 0]` and a smoothstep velocity
// ramp of length `ramp`, recomputed from its law (the test reads the body's own frame).
template <int D>
double body_shift(const CaseSetup<D>& s, int body, double t) {
  return s.motions[static_cast<std::size_t>(body)].pose(t).d.x();
}

// --- Closed box, constant acceleration --------------------------------------------------------

template <int D>
void accelerated_closed_box(double dp, double tol) {
  const double L = 0.2, W = 0.1, H = 0.1, a = 2.0, ramp = 0.02, t_end = 0.16, t_avg = 0.06;
  std::ostringstream c;
  c << "dim: " << D << "\ndp: " << dp << "\ntime: {end: " << t_end << "}\nbodies:\n";
  if (D == 2) {
    c << "  - {name: box, kind: boundary, shape: {box: {min: [0, 0], max: [" << L << ", " << H
      << "]}}, layers: 3, motion: {type: linear, acceleration: [" << a << ", 0], ramp: " << ramp
      << "}}\n"
      << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [" << L << ", " << H
      << "]}}}\n";
  } else {
    c << "  - {name: box, kind: boundary, shape: {box: {min: [0, 0, 0], max: [" << L << ", " << W
      << ", " << H << "]}}, layers: 4, motion: {type: linear, acceleration: [" << a
      << ", 0, 0], ramp: " << ramp << "}}\n"
      << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0, 0], max: [" << L << ", " << W
      << ", " << H << "]}}}\n";
  }
  CaseSetup<D> setup = setup_from<D>(c.str());
  Simulation<D> sim = make_simulation<D>(setup, std::move(setup.particles));
  const auto n0 = fluid_totals(sim.particles());
  double sum_dp = 0.0, sum_dx = 0.0;  // fitted L dp/dx, strip difference
  double impulse = 0.0;               // time integral of the force gauge on the (moving) box
  int samples = 0;
  while (sim.time() < t_end) {
    sim.step();
    const auto& ps = sim.particles();
    const double shift = body_shift(setup, 0, sim.time());
    // The symplectic corrector moves the fluid with the forces of the last evaluation, which
    // the force gauge reads: its impulse is exactly the fluid's momentum change.
    impulse += sim.dt() * body_load(ps, sim.acceleration(), 0, Eigen::Vector3d::Zero()).force.x();
    // No fluid particle leaves the box (its inner faces are at 0 and L in the box frame).
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (!is_fluid(ps.role[i])) continue;
      const double xr = ps.pos[i].x() - shift;
      ASSERT_GT(xr, 0.0) << "t = " << sim.time();
      ASSERT_LT(xr, L) << "t = " << sim.time();
      ASSERT_GT(ps.pos[i][D - 1], 0.0);
      ASSERT_LT(ps.pos[i][D - 1], H);
    }
    if (sim.time() < t_avg || sim.steps() % 5 != 0) continue;
    // The pressure gradient along the acceleration: a least-squares fit of p against the
    // box-frame x over every fluid particle (the depths are the same at every x, so
    // hydrostatics do not bias it), and the mean pressures of strips 2 dp wide along the rear
    // and the front wall.
    const auto& p = sim.pressure();
    double sx = 0, sp = 0, sxx = 0, sxp = 0, pr = 0, pf = 0;
    int n = 0, nr = 0, nf = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (!is_fluid(ps.role[i])) continue;
      const double x = ps.pos[i].x() - shift;
      sx += x;
      sp += p[i];
      sxx += x * x;
      sxp += x * p[i];
      ++n;
      if (x < 2.0 * dp) {
        pr += p[i];
        ++nr;
      } else if (x > L - 2.0 * dp) {
        pf += p[i];
        ++nf;
      }
    }
    ASSERT_GT(nr, 0);
    ASSERT_GT(nf, 0);
    sum_dp += -(n * sxp - sx * sp) / (n * sxx - sx * sx) * L;
    sum_dx += pr / nr - pf / nf;
    ++samples;
  }
  ASSERT_GT(samples, 50);
  const double measured = sum_dp / samples, expected = kRho0 * a * L;
  const double strips = sum_dx / samples;
  EXPECT_NEAR(measured, expected, tol * expected)
      << D << "D: -dp/dx L = " << measured << " Pa, rho a L = " << expected << " Pa";
  // The force gauge on the moving box: its impulse is minus the fluid's momentum (per metre in
  // 2D), which is M times the box velocity up to the acoustic oscillation.
  double momentum = 0.0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    if (is_fluid(sim.particles().role[i]))
      momentum += sim.particles().mass[i] * sim.particles().velocity(i).x();
  // (plus one rounding of the stored velocities, kStateEps of the momentum since they all move
  // one way: tests/state_precision.hpp; measured 4e-8 of it with the float state)
  EXPECT_NEAR(impulse, -momentum, stored_tol(momentum, 1e-9 * std::abs(momentum)))
      << "force gauge on the moving box";
  const double box_v = setup.motions[0].pose(sim.time()).dv.x();
  EXPECT_NEAR(momentum, n0.mass * box_v, 0.02 * n0.mass * box_v);
  const auto n1 = fluid_totals(sim.particles());
  EXPECT_EQ(n1.count, n0.count);
  EXPECT_EQ(n1.mass, n0.mass);
  EXPECT_EQ(sim.excluded().total(), 0u);
  std::printf(
      "[ measured ] %dD closed box: gauge impulse %.6f N s, fluid momentum %.6f kg m/s, "
      "M v_box %.6f\n",
      D, impulse, momentum, n0.mass * box_v);
  std::printf(
      "[ measured ] %dD closed box: -dp/dx L %.2f Pa vs rho a L %.2f Pa (%+.2f %%); wall "
      "strips (centres %.1f dp apart) differ by %.2f Pa\n",
      D, measured, expected, 100.0 * (measured / expected - 1.0), L / dp - 2.0, strips);
}

TEST(MovingBodies, AcceleratedClosedBoxPressureIsRhoAL2D) {
  accelerated_closed_box<2>(0.005, 0.05);
}
TEST(MovingBodies, AcceleratedClosedBoxPressureIsRhoAL3D) {
  accelerated_closed_box<3>(0.01, 0.08);
}

// --- Open tank, constant acceleration ----------------------------------------------------------

// Least-squares slope of the free surface: the top fluid particle of each dp-wide column in the
// tank frame, columns more than 4 dp from the walls.
template <int D>
double surface_slope(const ParticleSet<D>& ps, double shift, double L, double dp) {
  const int ncol = static_cast<int>(std::lround(L / dp));
  std::vector<double> top(static_cast<std::size_t>(ncol), -1e9);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!is_fluid(ps.role[i])) continue;
    const int c = static_cast<int>(std::floor((ps.pos[i].x() - shift) / dp));
    if (c >= 0 && c < ncol) top[c] = std::max(top[c], ps.pos[i][D - 1]);
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (int c = 4; c < ncol - 4; ++c) {
    const double x = (c + 0.5) * dp;
    sx += x;
    sy += top[c];
    sxx += x * x;
    sxy += x * top[c];
    ++n;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST(MovingBodies, AcceleratedOpenTankSurfaceSlopeIsAOverG) {
  const double L = 0.4, H = 0.1, dp = 0.005, a = 0.5, ramp = 0.05;
  const double k = M_PI / L, omega = std::sqrt(kG * k * std::tanh(k * H));
  const double period = 2.0 * M_PI / omega, t0 = 0.1, t_end = t0 + period;
  std::ostringstream c;
  c << "dim: 2\ndp: " << dp << "\ntime: {end: " << t_end << "}\nbodies:\n"
    << "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [" << L
    << ", 0.2]}}, layers: 3, open: [ymax], motion: {type: linear, acceleration: [" << a
    << ", 0], ramp: " << ramp << "}}\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [" << L << ", " << H
    << "]}}}\n";
  CaseSetup<2> setup = setup_from<2>(c.str());
  Simulation<2> sim = make_simulation<2>(setup, std::move(setup.particles));
  double sum = 0.0;
  int samples = 0;
  while (sim.time() < t_end) {
    sim.step();
    if (sim.time() < t0 || sim.steps() % 10 != 0) continue;
    sum += surface_slope(sim.particles(), body_shift(setup, 0, sim.time()), L, dp);
    ++samples;
  }
  ASSERT_GT(samples, 100);
  const double slope = -sum / samples;  // the water piles up at the rear (x = 0)
  EXPECT_NEAR(slope, a / kG, 0.1 * a / kG) << "mean surface slope over one sloshing period";
  EXPECT_EQ(sim.excluded().total(), 0u);
  std::printf("[ measured ] open tank: mean slope %.5f vs a/g %.5f (%+.2f %%) over %.3f s\n", slope,
              a / kG, 100.0 * (slope * kG / a - 1.0), period);
}

// --- Stokes' first problem ---------------------------------------------------------------------

// u(y, t) of a layer of depth H with a free surface on a plate started at U at t = 0: the
// erfc of the semi-infinite problem with its images in the surface and the plate.
double stokes_layer(double y, double t, double H, double U, double nu) {
  const double s = 2.0 * std::sqrt(nu * t);
  double u = 0.0, sign = 1.0;
  for (int n = 0; n < 20; ++n, sign = -sign)
    u += sign * (std::erfc((2 * n * H + y) / s) + std::erfc((2 * (n + 1) * H - y) / s));
  return U * u;
}

TEST(MovingBodies, StokesFirstProblemMatchesErfc) {
  // A 0.06 m deep layer on a long plate that starts moving at U at t = 0, laminar viscosity
  // nu = 1e-3 m^2/s (a thick oil): 2 sqrt(nu t) = 14 dp at t = 0.3 s. Gravity is small (the
  // sound speed comes from coefsound instead) so the layer's free ends do not slump, and there
  // are no end walls (their pressure would drive a return flow); the profile is taken over the
  // middle 0.1 m of the 0.4 m layer.
  const double dp = 0.0025, H = 0.06, Lx = 0.4, U = 0.05, nu = 1e-3, t_end = 0.3;
  std::ostringstream c;
  c << "dim: 2\ndp: " << dp << "\n"
    << "physics: {gravity: [0, -0.01], coefsound: 600, viscosity: {model: laminar, nu: " << nu
    << "}}\n"
    << "time: {end: " << t_end << "}\nbodies:\n"
    << "  - {name: plate, kind: boundary, shape: {box: {min: [-0.1, " << -3 * dp
    << "], max: [0.5, 0]}}, walls: outside, layers: 3, motion: {type: linear, velocity: [" << U
    << ", 0]}}\n"
    << "  - {name: oil, kind: fluid, shape: {box: {min: [0, 0], max: [" << Lx << ", " << H
    << "]}}}\n";
  CaseSetup<2> setup = setup_from<2>(c.str());
  Simulation<2> sim = make_simulation<2>(setup, std::move(setup.particles));
  while (sim.time() < t_end) sim.step();
  const double t = sim.time();
  const auto& ps = sim.particles();
  const int nbin = static_cast<int>(std::lround(H / dp)) - 2;  // below the surface rows
  std::vector<double> u(nbin, 0.0);
  std::vector<int> cnt(nbin, 0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!is_fluid(ps.role[i])) continue;
    const double x = ps.pos[i].x(), y = ps.pos[i].y();
    if (x < 0.15 || x > 0.25) continue;
    const int b = static_cast<int>(std::floor(y / dp));
    if (b < 0 || b >= nbin) continue;
    u[b] += ps.vel[i].x();
    ++cnt[b];
  }
  double worst = 0.0;
  std::ostringstream profile;
  for (int b = 0; b < nbin; ++b) {
    ASSERT_GT(cnt[b], 10);
    const double y = (b + 0.5) * dp, exact = stokes_layer(y, t, H, U, nu);
    worst = std::max(worst, std::abs(u[b] / cnt[b] - exact));
    profile << " y " << y << ": " << u[b] / cnt[b] / U << " vs " << exact / U << "\n";
  }
  EXPECT_LT(worst, 0.05 * U) << "largest error of the row-averaged velocity:\n" << profile.str();
  std::printf("[ measured ] Stokes' first problem at t = %.3f s: max |u - exact| = %.2f %% of U\n",
              t, 100.0 * worst / U);
}

// --- Sloshing frequency ------------------------------------------------------------------------

// The free sloshing period of a tank 0.2 m long with 0.048 m of water, swayed at 2 mm
// amplitude for one period at the first mode's period and then held: the fluid's centre of mass
// then swings at omega_1, measured by a least-squares fit of a sinusoid over the 2.25 periods
// that follow. Returns the relative error of the measured period against linear theory.
double sloshing_period_error(double dp) {
  const double L = 0.2, H = 0.048, A = 0.002;
  const double k = M_PI / L, omega = std::sqrt(kG * k * std::tanh(k * H));
  const double period = 2.0 * M_PI / omega, t_end = 3.5 * period;
  std::ostringstream c;
  c << "dim: 2\ndp: " << dp << "\ntime: {end: " << t_end << "}\nbodies:\n"
    << "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [" << L
    << ", 0.12]}}, layers: 3, open: [ymax], motion: {type: sinusoidal, amplitude: " << A
    << ", period: " << period << ", direction: [1, 0], stop: " << period << "}}\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [" << L << ", " << H
    << "]}}}\n";
  CaseSetup<2> setup = setup_from<2>(c.str());
  Simulation<2> sim = make_simulation<2>(setup, std::move(setup.particles));
  std::vector<double> ts, xs;
  while (sim.time() < t_end) {
    sim.step();
    if (sim.time() < 1.25 * period) continue;  // free oscillation only
    const auto& ps = sim.particles();
    double sx = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (is_fluid(ps.role[i])) {
        sx += ps.pos[i].x();
        ++n;
      }
    ts.push_back(sim.time());
    xs.push_back(sx / n - 0.5 * L);
  }
  // x(t) = a cos(w t) + b sin(w t) + c fitted by least squares for each trial w; the best w
  // (scanned over +-30 % of omega_1 in steps of 0.01 %) is the sloshing frequency.
  auto fit = [&](double w) {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < ts.size(); ++i) {
      const Eigen::Vector3d f(std::cos(w * ts[i]), std::sin(w * ts[i]), 1.0);
      m += f * f.transpose();
      r += f * xs[i];
    }
    const Eigen::Vector3d coef = m.ldlt().solve(r);
    double e = 0.0;
    for (std::size_t i = 0; i < ts.size(); ++i) {
      const Eigen::Vector3d f(std::cos(w * ts[i]), std::sin(w * ts[i]), 1.0);
      e += std::pow(xs[i] - f.dot(coef), 2);
    }
    return std::make_pair(e, std::hypot(coef[0], coef[1]));
  };
  double best_w = 0.0, best_e = 1e300, amplitude = 0.0;
  for (double w = 0.7 * omega; w <= 1.3 * omega; w += 1e-4 * omega) {
    const auto [e, amp] = fit(w);
    if (e < best_e) {
      best_e = e;
      best_w = w;
      amplitude = amp;
    }
  }
  EXPECT_GT(amplitude, 0.5e-3) << "the fluid does not slosh (dp " << dp << ")";
  const double measured = 2.0 * M_PI / best_w;
  std::printf(
      "[ measured ] dp %.4f: sloshing period %.4f s vs linear theory %.4f s (%+.2f %%), "
      "centre of mass amplitude %.2f mm\n",
      dp, measured, period, 100.0 * (measured / period - 1.0), 1e3 * amplitude);
  return measured / period - 1.0;
}

// At amplitudes of the order of dp the particle arrangement stiffens the surface (a known
// WCSPH lattice effect) and DBC walls sit ~dp/2 off, so the coarse period is short by several
// per cent; it must converge to linear theory as dp halves (first order or better) and be
// within 5 % at 24 particles over the depth.
TEST(MovingBodies, SwayedTankSloshesAtTheFirstModeFrequency) {
  const double coarse = sloshing_period_error(0.004), fine = sloshing_period_error(0.002);
  EXPECT_LT(std::abs(fine), 0.6 * std::abs(coarse)) << "no convergence to linear theory";
  EXPECT_LT(std::abs(fine), 0.05) << "sloshing period against linear theory at dp = 2 mm";
}

}  // namespace
}  // namespace swell
