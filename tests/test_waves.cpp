// waves/: dispersion, paddle transfer functions, paddle signals (regular first and second
// order, solitary, focused, irregular), spectra and the validity assessment, each against an
// independent computation or a limit that theory fixes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "waves/dispersion.hpp"
#include "waves/record.hpp"
#include "waves/spectrum.hpp"
#include "waves/theory.hpp"
#include "waves/wavemaker.hpp"

namespace swell::waves {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double g = 9.81;

// Wave number by bisection on omega^2 = g k tanh(kd): an independent root finder.
double k_bisection(double omega, double d) {
  double lo = 1e-12, hi = 1e4;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g * mid * std::tanh(mid * d) < omega * omega ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(WaveDispersion, MatchesBisectionAndLimits) {
  for (double d : {0.05, 0.4, 0.7, 3.0, 50.0})
    for (double T : {0.5, 1.0, 2.0, 5.0, 12.0}) {
      const double w = 2 * kPi / T;
      const double k = wave_number(w, d, g);
      EXPECT_NEAR(k, k_bisection(w, d), 1e-12 * k) << d << " " << T;
      EXPECT_NEAR(g * k * std::tanh(k * d), w * w, 1e-13 * w * w);
    }
  // Deep water: L0 = g T^2 / (2 pi); shallow water: c = sqrt(g d).
  EXPECT_NEAR(wave_length(2.0, 100.0, g), g * 4.0 / (2 * kPi), 1e-9);
  EXPECT_NEAR(phase_speed(2 * kPi / 200.0, 0.1, g), std::sqrt(g * 0.1), 1e-4);
  EXPECT_NEAR(group_ratio(1e-9), 1.0, 1e-12);
  EXPECT_NEAR(group_ratio(40.0), 0.5, 1e-12);
  EXPECT_THROW(wave_number(0.0, 1.0, g), std::invalid_argument);
  EXPECT_THROW(wave_number(1.0, -1.0, g), std::invalid_argument);
}

// The general transfer function F = 4 k sinh(kd) I / (sinh 2kd + 2kd) by quadrature of
// I = int f(z) cosh k(d + z) dz: an independent check of the closed forms.
double transfer_quadrature(double k, double d, double hinge, bool piston) {
  const int n = 20000;
  double integral = 0.0;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) * d / n;  // height above the bed
    const double f = piston ? 1.0 : std::max(0.0, (s - hinge) / (d - hinge));
    integral += f * std::cosh(k * s) * d / n;
  }
  return 4 * k * std::sinh(k * d) * integral / (std::sinh(2 * k * d) + 2 * k * d);
}

TEST(WaveTransfer, PistonAndFlapAgainstQuadratureAndLimits) {
  const double d = 0.5;
  for (double kd : {0.1, 0.5, 1.0, 2.0, 4.0}) {
    const double k = kd / d;
    PaddleGeometry piston{PaddleGeometry::Type::Piston, d, 0.0};
    EXPECT_NEAR(transfer_function(piston, k), transfer_quadrature(k, d, 0, true), 1e-7);
    for (double hinge : {0.0, 0.1, -0.2}) {
      PaddleGeometry flap{PaddleGeometry::Type::Flap, d, hinge};
      EXPECT_NEAR(transfer_function(flap, k), transfer_quadrature(k, d, hinge, false), 1e-6)
          << "kd " << kd << " hinge " << hinge;
    }
    // Bottom-hinged flap in Dean & Dalrymple's form.
    const double sh = std::sinh(kd);
    const double dd = 4 * sh * (kd * sh - std::cosh(kd) + 1) / (kd * (std::sinh(2 * kd) + 2 * kd));
    EXPECT_NEAR(transfer_function({PaddleGeometry::Type::Flap, d, 0.0}, k), dd, 1e-12);
  }
  // Shallow water: piston H/S -> kd, bottom flap -> kd / 2; deep water: 2 and 2 (1 - 1/kd).
  EXPECT_NEAR(transfer_function({PaddleGeometry::Type::Piston, 1.0, 0}, 1e-3), 1e-3, 1e-8);
  EXPECT_NEAR(transfer_function({PaddleGeometry::Type::Flap, 1.0, 0}, 1e-3), 0.5e-3, 1e-8);
  EXPECT_NEAR(transfer_function({PaddleGeometry::Type::Piston, 1.0, 0}, 30.0), 2.0, 1e-12);
  EXPECT_NEAR(transfer_function({PaddleGeometry::Type::Flap, 1.0, 0}, 30.0), 2 * (1 - 1 / 30.0),
              1e-12);
  EXPECT_NEAR(transfer_function({PaddleGeometry::Type::Flap, 1.0, 0}, 400.0), 2 * (1 - 1 / 400.0),
              1e-12);
  EXPECT_THROW(transfer_function({PaddleGeometry::Type::Flap, 1.0, 1.0}, 1.0),
               std::invalid_argument);
}

TEST(WavePaddle, RegularFirstAndSecondOrder) {
  const PaddleGeometry piston{PaddleGeometry::Type::Piston, 0.6, 0.0};
  const double H = 0.08, T = 1.6, w = 2 * kPi / T;
  const double k = k_bisection(w, 0.6), kd = k * 0.6;
  const double F = 2 * (std::cosh(2 * kd) - 1) / (std::sinh(2 * kd) + 2 * kd);
  const PaddleSignal s1 = regular_paddle(piston, H, T, 1, 0.3, g);
  ASSERT_EQ(s1.components.size(), 1u);
  EXPECT_NEAR(s1.components[0].amplitude, 0.5 * H / F, 1e-12);
  EXPECT_NEAR(s1.displacement(0.7), 0.5 * H / F * std::sin(w * 0.7 + 0.3), 1e-12);
  // Velocity is the derivative of displacement.
  const double e = 1e-6;
  EXPECT_NEAR(s1.velocity(0.7), (s1.displacement(0.7 + e) - s1.displacement(0.7 - e)) / (2 * e),
              1e-8);
  const PaddleSignal s2 = regular_paddle(piston, H, T, 2, 0.0, g);
  ASSERT_EQ(s2.components.size(), 2u);
  EXPECT_DOUBLE_EQ(s2.components[1].omega, 2 * w);
  // In shallow water Madsen's term is the bound second harmonic of Stokes' theory, a2 = 3 H^2 /
  // (16 k^2 d^3), made by a piston of transfer 2kd at 2 omega: 3 H^2 / (32 k^3 d^4).
  const PaddleGeometry shallow{PaddleGeometry::Type::Piston, 0.1, 0.0};
  const double Ts = 20.0, ks = k_bisection(2 * kPi / Ts, 0.1), Hs = 0.005;
  const PaddleSignal sh = regular_paddle(shallow, Hs, Ts, 2, 0.0, g);
  const double expect = 3 * Hs * Hs / (32 * std::pow(ks, 3) * std::pow(0.1, 4));
  EXPECT_NEAR(sh.components[1].amplitude / expect, 1.0, 0.01);
  // Linear components through linear_paddle give the same first-order paddle.
  const PaddleSignal lin = linear_paddle(piston, {{0.5 * H, w, 0.3}}, g);
  EXPECT_NEAR(lin.components[0].amplitude, s1.components[0].amplitude, 1e-14);
  EXPECT_THROW(regular_paddle({PaddleGeometry::Type::Flap, 0.6, 0.0}, H, T, 2),
               std::invalid_argument);
  EXPECT_THROW(regular_paddle(piston, H, T, 3), std::invalid_argument);
  EXPECT_THROW(regular_paddle(piston, -H, T, 1), std::invalid_argument);
}

TEST(WavePaddle, GoringSolitaryTrajectory) {
  const double d = 0.4, H = 0.08;
  const PaddleSignal s = solitary_paddle({PaddleGeometry::Type::Piston, d, 0.0}, H, g);
  const SolitaryPaddle& p = s.soliton;
  EXPECT_NEAR(p.kappa, std::sqrt(3 * H / (4 * d * d * d)), 1e-14);
  EXPECT_NEAR(p.stroke, 2 * H / (p.kappa * d), 1e-14);
  EXPECT_DOUBLE_EQ(s.displacement(0.0), 0.0);
  // The full stroke is covered to within Goring's 0.1 %.
  EXPECT_NEAR(s.displacement(p.duration) / p.stroke, 1.0, 2e-3);
  EXPECT_EQ(s.velocity(-1.0), 0.0);
  EXPECT_EQ(s.velocity(p.duration + 1.0), 0.0);
  // The paddle moves with the depth-averaged wave velocity c eta / (d + eta) at its own position:
  // the displacement's finite-difference derivative and the formula at the wave's crest.
  const double mid = 0.5 * p.duration, e = 1e-6;
  for (double t : {0.3 * p.duration, mid, 0.8 * p.duration}) {
    const double fd = (s.displacement(t + e) - s.displacement(t - e)) / (2 * e);
    EXPECT_NEAR(s.velocity(t), fd, 1e-7 * p.celerity);
    const double xi = s.displacement(t) + p.start;  // position in the wave's frame
    const double ch = std::cosh(p.kappa * (p.celerity * (t - mid) - xi));
    const double eta = H / (ch * ch);
    EXPECT_NEAR(s.velocity(t), p.celerity * eta / (d + eta), 1e-12);
  }
  EXPECT_NEAR(s.velocity(mid), p.celerity * H / (d + H), 1e-12);
  EXPECT_THROW(solitary_paddle({PaddleGeometry::Type::Flap, d, 0.0}, H), std::invalid_argument);
}

// The target elevation a paddle signal carries (for active absorption): the second-order regular
// wave is Stokes' wave of waves/theory.hpp, a linear signal is its own surface components, and
// the solitary target is the wave Goring's paddle follows: dX/dt = c eta / (d + eta) at X(t).
TEST(WavePaddle, TargetElevation) {
  const PaddleGeometry piston{PaddleGeometry::Type::Piston, 0.4, 0.0};
  const PaddleSignal reg = regular_paddle(piston, 0.06, 1.3, 2, 0.0, g);
  for (double t : {0.0, 0.37, 1.1, 2.9})
    for (double x : {0.0, 0.25, 1.7})
      EXPECT_NEAR(reg.elevation(t, x), stokes2_elevation(0.06, 1.3, 0.4, x, t, 0.0, g), 1e-12);
  EXPECT_NEAR(reg.peak_omega(), 2 * kPi / 1.3, 1e-12);

  const std::vector<SurfaceComponent> surface = {{0.02, 4.0, 0.3}, {0.01, 6.5, -1.2}};
  const PaddleSignal lin = linear_paddle(piston, surface, g);
  for (double t : {0.0, 0.8, 3.3}) {
    EXPECT_NEAR(lin.elevation(t, 0.0),
                0.02 * std::cos(4.0 * t + 0.3) + 0.01 * std::cos(6.5 * t - 1.2), 1e-14);
    EXPECT_NEAR(lin.elevation(t, 1.3), linear_elevation(surface, 0.4, 1.3, t, g), 1e-12);
  }
  EXPECT_DOUBLE_EQ(lin.peak_omega(), 4.0);

  const PaddleSignal sol = solitary_paddle(piston, 0.08, g);
  const double c = sol.soliton.celerity, d = 0.4;
  double peak = 0.0;
  for (double t = 0.05; t < sol.soliton.duration; t += 0.05) {
    const double x = sol.displacement(t), eta = sol.elevation(t, x);
    EXPECT_NEAR(sol.velocity(t), c * eta / (d + eta), 1e-9 * c) << "t = " << t;
    peak = std::max(peak, eta);
  }
  EXPECT_NEAR(peak, 0.08, 1e-3);
  EXPECT_EQ(sol.peak_omega(), 0.0);
}

// A paddle record propagated by linear theory (waves/record.hpp) gives the target wave of the
// signal it samples: a regular first-order piston signal of 60 s at 50 Hz, predicted 4 m down
// the flume, against the target elevation once the wave has arrived (before that the periodic
// transform's wrap-around and the missing start-up are visible).
TEST(WaveRecord, PropagatedRecordIsTheTargetWave) {
  const PaddleGeometry piston{PaddleGeometry::Type::Piston, 0.5, 0.0};
  const PaddleSignal sig = regular_paddle(piston, 0.05, 1.1, 1, 0.3, g);
  const double dt = 0.02;
  std::vector<double> x;
  // Ramped up over 3 periods (smoothstep), as a run's paddle is: an abrupt start would send
  // short, slow waves that arrive at 4 m only tens of seconds later.
  const auto ramp = [](double t) {
    const double s = std::min(t / 3.3, 1.0);
    return s * s * (3 - 2 * s);
  };
  for (int i = 0; i < 3000; ++i) x.push_back(ramp(i * dt) * sig.displacement(i * dt));
  const std::vector<double> eta = propagate_paddle_record(x, dt, piston, 4.0, g);
  ASSERT_EQ(eta.size(), x.size());
  double worst = 0.0;
  for (int i = 600; i < 2750; ++i)
    worst = std::max(worst, std::abs(eta[i] - sig.elevation(i * dt, 4.0)));
  EXPECT_LT(worst, 0.01 * 0.025) << "worst " << worst;
  // At the paddle (x = 0) it is the transfer function times the displacement a quarter period on.
  const std::vector<double> at0 = propagate_paddle_record(x, dt, piston, 0.0, g);
  double worst0 = 0.0;
  for (int i = 200; i < 2800; ++i)
    if (i * dt > 3.3) worst0 = std::max(worst0, std::abs(at0[i] - sig.elevation(i * dt, 0.0)));
  EXPECT_LT(worst0, 0.01 * 0.025) << "worst " << worst0;
  EXPECT_THROW(propagate_paddle_record({0.0, 1.0}, dt, piston, 1.0, g), std::invalid_argument);
}

TEST(WaveSpectrum, ShapeAndIrregularSea) {
  SpectrumSpec j;
  j.hs = 0.1;
  j.tp = 1.5;
  j.gamma = 3.3;
  SpectrumSpec pm = j;
  pm.shape = SpectrumSpec::Shape::PiersonMoskowitz;
  // Peak at fp; the JONSWAP peak is gamma times the Pierson-Moskowitz one.
  const double fp = 1 / j.tp;
  EXPECT_NEAR(spectrum_shape(j, fp) / spectrum_shape(pm, fp), 3.3, 1e-12);
  double best = 0, fbest = 0;
  for (int i = 1; i < 20000; ++i) {
    const double f = i * 1e-4 * 3;
    if (spectrum_shape(j, f) > best) best = spectrum_shape(j, f), fbest = f;
  }
  EXPECT_NEAR(fbest, fp, 3e-4);
  const auto sea = irregular_sea(j);
  ASSERT_EQ(sea.size(), 200u);
  double m0 = 0, phase_mean = 0;
  for (const auto& c : sea) {
    m0 += 0.5 * c.amplitude * c.amplitude;
    EXPECT_GE(c.phase, 0.0);
    EXPECT_LT(c.phase, 2 * kPi);
    phase_mean += c.phase / sea.size();
  }
  EXPECT_NEAR(4 * std::sqrt(m0), 0.1, 1e-12);
  EXPECT_NEAR(phase_mean, kPi, 0.5);  // uniform phases: mean pi, sd of the mean ~0.13
  // Reproducible: the same seed gives the same phases; another seed other ones.
  const auto again = irregular_sea(j);
  for (std::size_t i = 0; i < sea.size(); ++i) EXPECT_EQ(sea[i].phase, again[i].phase);
  SpectrumSpec other = j;
  other.seed = 2;
  EXPECT_NE(irregular_sea(other)[0].phase, sea[0].phase);
  // The elevation synthesised over one repeat period has variance m0 (Parseval for the set).
  const double repeat = 200 / (3 / j.tp - 0.5 / j.tp);
  double var = 0;
  const int n = 2000;  // more than twice the highest harmonic index (~170)
  for (int i = 0; i < n; ++i) {
    const double eta = linear_elevation(sea, 0.6, 0.0, repeat * i / n, g);
    var += eta * eta / n;
  }
  EXPECT_NEAR(var / m0, 1.0, 1e-6);
  j.gamma = 0.5;
  EXPECT_THROW(irregular_sea(j), std::invalid_argument);
}

TEST(WaveSpectrum, FocusedGroupCrestsAtFocus) {
  SpectrumSpec s;
  s.tp = 1.4;
  s.components = 60;
  const double A = 0.05, xf = 6.0, tf = 20.0, d = 0.6;
  const auto group = focused_group(s, A, xf, tf, d, g);
  EXPECT_NEAR(linear_elevation(group, d, xf, tf, g), A, 1e-12);
  // Nowhere else on the focus line in time is the elevation as high.
  for (double t = 0; t < 40; t += 0.05)
    if (std::abs(t - tf) > 0.2) EXPECT_LT(linear_elevation(group, d, xf, t, g), 0.9 * A) << t;
}

// Second-order pair kernels (waves/theory.hpp) against what theory fixes independently: the sum
// kernel of a component with itself is Stokes' second harmonic; the difference kernel of two
// close frequencies is Longuet-Higgins & Stewart's (1962) set-down from the radiation stress;
// the bound wave conserves mass with its flux; the subharmonic piston supplies that flux.
TEST(WaveSecondOrder, KernelsAgainstStokesSetDownAndMassConservation) {
  for (double d : {0.3, 0.6})
    for (double T : {0.8, 1.2, 2.0, 4.0}) {
      const double w = 2 * kPi / T, k = k_bisection(w, d), a = 0.01;
      // a2 = a^2 G+(i, i) / 2 = a stokes2_harmonic_ratio(k, d, 2a).
      EXPECT_NEAR(0.5 * a * a * second_order_kernel(w, k, w, k, d, true, g),
                  a * stokes2_harmonic_ratio(k, d, 2 * a), 1e-12)
          << "d " << d << " T " << T;
      // Set-down under a narrow group, -g (2 cg / c - 1/2) / (g d - cg^2) per a_i a_j.
      const double c = w / k, n = 0.5 * (1 + 2 * k * d / std::sinh(2 * k * d)), cg = n * c;
      const double lhs = -g * (2 * cg / c - 0.5) / (g * d - cg * cg);
      const double w2 = w * (1 - 1e-5), k2 = k_bisection(w2, d);
      const double gm = second_order_kernel(w, k, w2, k2, d, false, g);
      EXPECT_NEAR(gm / lhs, 1.0, 1e-3) << "d " << d << " T " << T;
      EXPECT_LT(gm, 0.0);
      // The piston then moves with the set-down's flux: X2' = cg eta_b / d (the volume term
      // (1/F_i - 1/F_j) / 2d vanishes as the band narrows).
      const double p = subharmonic_piston(w, k, w2, k2, d, g);
      EXPECT_NEAR(p * (w - w2) * d / (cg * lhs), 1.0, 1e-3);
    }
  // Two distinct components: symmetric kernel; mass conservation of the bound wave,
  // (w_i - w_j) G- = (k_i - k_j) F, F from the bound potential and the Stokes flux.
  const double d = 0.4;
  for (const auto& [wi, wj] : {std::pair{6.0, 5.0}, {5.0, 2.0}, {9.0, 8.5}, {3.0, 1.0}}) {
    const double ki = k_bisection(wi, d), kj = k_bisection(wj, d);
    const double gij = second_order_kernel(wi, ki, wj, kj, d, false, g);
    EXPECT_NEAR(gij, second_order_kernel(wj, kj, wi, ki, d, false, g), 1e-12 * std::abs(gij));
    EXPECT_NEAR((wi - wj) * gij, (ki - kj) * subharmonic_flux(wi, ki, wj, kj, d, g),
                1e-10 * std::abs((wi - wj) * gij));
    EXPECT_NEAR(subharmonic_piston(wi, ki, wj, kj, d, g), -subharmonic_piston(wj, kj, wi, ki, d, g),
                1e-12 * std::abs(gij));
  }
  const double k1 = k_bisection(5.0, d);
  EXPECT_THROW(second_order_kernel(5.0, k1, 5.0, k1, d, false, g), std::invalid_argument);
  EXPECT_THROW(subharmonic_piston(5.0, k1, 5.0, k1, d, g), std::invalid_argument);
}

// The kernels at finite separation against the published form, written out independently here:
// Sharma & Dean's (1981) sum and difference kernels as Forristall (2000, J. Phys. Oceanogr.
// 30:1931) writes them, R = k tanh(k d), per unordered pair (so halved). And the subharmonic
// piston term P with its second part, the progressive waves' X1 eta1 volume -(1/F_i - 1/F_j)/2d,
// F the piston's transfer function from its own formula: flipping that part's sign moves P by
// 4 % for the flume case's pair (0.65 / 0.80 Hz in 0.4 m).
double forristall_kernel(double ki, double kj, double d, bool sum) {
  const double ri = ki * std::tanh(ki * d), rj = kj * std::tanh(kj * d);
  const double si = std::sqrt(ri), sj = std::sqrt(rj);
  const double s = sum ? 1.0 : -1.0, km = std::abs(ki + s * kj), sp = si + s * sj;
  const double num = sp * (sj * (ki * ki - ri * ri) + s * si * (kj * kj - rj * rj)) +
                     2 * sp * sp * (ki * kj - s * ri * rj);
  const double dd = num / (sp * sp - km * std::tanh(km * d));
  return 0.5 * ((dd - (ki * kj - s * ri * rj)) / std::sqrt(ri * rj) + ri + rj);
}

TEST(WaveSecondOrder, KernelsAndPistonAgainstThePublishedForm) {
  const double d = 0.4;
  for (const auto& [fi, fj] :
       {std::pair{0.65, 0.80}, {0.70, 0.72}, {0.50, 1.50}, {0.30, 2.00}, {1.20, 0.90}}) {
    const double wi = 2 * kPi * fi, wj = 2 * kPi * fj;
    const double ki = k_bisection(wi, d), kj = k_bisection(wj, d);
    for (const bool sum : {false, true}) {
      const double ref = forristall_kernel(ki, kj, d, sum);
      EXPECT_NEAR(second_order_kernel(wi, ki, wj, kj, d, sum, g), ref, 1e-9 * std::abs(ref))
          << fi << " / " << fj << (sum ? " sum" : " difference");
    }
  }
  const double wi = 2 * kPi * 0.65, wj = 2 * kPi * 0.80;
  const double ki = k_bisection(wi, d), kj = k_bisection(wj, d);
  const auto piston_f = [&](double k) {
    return 2 * (std::cosh(2 * k * d) - 1) / (std::sinh(2 * k * d) + 2 * k * d);
  };
  const double first = forristall_kernel(ki, kj, d, false) / ((ki - kj) * d);
  const double second = -(1 / piston_f(ki) - 1 / piston_f(kj)) / (2 * d);
  EXPECT_NEAR(subharmonic_piston(wi, ki, wj, kj, d, g), first + second, 1e-9 * std::abs(first));
  EXPECT_GT(std::abs(second), 0.01 * std::abs(first));  // 2 % of the first here: present, tested
}

// The second-order signal of a component set: the paddle and the target elevation are the
// linear ones plus the pair terms summed directly here (over 300 components, so the evaluation's
// blocks of 128 and their edges are crossed); the velocity is the displacement's derivative.
TEST(WaveSecondOrder, PairSignalIsTheDirectSum) {
  SpectrumSpec j;
  j.hs = 0.06;
  j.tp = 1.3;
  j.components = 300;
  const auto sea = irregular_sea(j);
  const double d = 0.45;
  const PaddleGeometry piston{PaddleGeometry::Type::Piston, d, 0.0};
  const PaddleSignal lin = linear_paddle(piston, sea, g);
  const PaddleSignal so = second_order_paddle(piston, sea, g);
  ASSERT_EQ(so.pair_components, 300u);
  ASSERT_EQ(so.components.size(), lin.components.size());
  std::vector<double> k(sea.size());
  for (std::size_t i = 0; i < sea.size(); ++i) k[i] = k_bisection(sea[i].omega, d);
  for (double t : {0.0, 3.7, 41.2}) {
    double x2 = 0, v2 = 0, e0 = 0, e1 = 0;
    for (std::size_t i = 0; i < sea.size(); ++i)
      for (std::size_t jj = i + 1; jj < sea.size(); ++jj) {
        const auto &a = sea[i], &b = sea[jj];
        const double aa = a.amplitude * b.amplitude;
        const double psi = (a.omega - b.omega) * t + a.phase - b.phase;
        const double p = aa * subharmonic_piston(a.omega, k[i], b.omega, k[jj], d, g);
        const double gm = aa * second_order_kernel(a.omega, k[i], b.omega, k[jj], d, false, g);
        x2 += p * std::sin(psi);
        v2 += p * (a.omega - b.omega) * std::cos(psi);
        e0 += gm * std::cos(psi);
        e1 += gm * std::cos(psi - (k[i] - k[jj]) * 2.5);
      }
    const double scale = 1e-9 + 1e-6 * std::abs(x2);
    EXPECT_NEAR(so.displacement(t) - lin.displacement(t), x2, scale) << t;
    EXPECT_NEAR(so.velocity(t) - lin.velocity(t), v2, 1e-9 + 1e-6 * std::abs(v2)) << t;
    EXPECT_NEAR(so.elevation(t, 0.0) - lin.elevation(t, 0.0), e0, 1e-9) << t;
    EXPECT_NEAR(so.elevation(t, 2.5) - lin.elevation(t, 2.5), e1, 1e-9) << t;
    const double e = 1e-6;
    EXPECT_NEAR(so.velocity(t), (so.displacement(t + e) - so.displacement(t - e)) / (2 * e), 1e-7);
  }
  // Two components: where their crests meet (the group's maximum, psi_1 = psi_2) the bound
  // wave is a set-down, a1 a2 G- < 0, and half a group period later a set-up of the same size;
  // the paddle moves back under the group's maximum (X2' < 0 there).
  const std::vector<SurfaceComponent> pair = {{0.02, 4.0, 0.0}, {0.015, 5.0, 0.0}};
  const PaddleSignal two = second_order_paddle(piston, pair, g);
  const PaddleSignal two_lin = linear_paddle(piston, pair, g);
  const double gm =
      second_order_kernel(5.0, k_bisection(5.0, d), 4.0, k_bisection(4.0, d), d, false, g);
  const double t_max = 2 * kPi, t_min = kPi;  // (5 - 4) t = 2 pi and pi
  EXPECT_NEAR(two.elevation(t_max, 0.0) - two_lin.elevation(t_max, 0.0), 0.02 * 0.015 * gm, 1e-12);
  EXPECT_LT(gm, 0.0);
  EXPECT_NEAR(two.elevation(t_min, 0.0) - two_lin.elevation(t_min, 0.0), -0.02 * 0.015 * gm, 1e-12);
  EXPECT_LT(two.velocity(t_max) - two_lin.velocity(t_max), 0.0);
  // One component has no pair; a flap or a repeated frequency is refused.
  EXPECT_EQ(second_order_paddle(piston, {sea[0]}, g).pair_components, 0u);
  EXPECT_THROW(second_order_paddle({PaddleGeometry::Type::Flap, d, 0.0}, sea, g),
               std::invalid_argument);
  EXPECT_THROW(second_order_paddle(piston, {sea[0], sea[0]}, g), std::invalid_argument);
}

TEST(WaveTheory, StokesSecondOrderCrestAndTrough) {
  const double H = 0.1, T = 2.0, d = 0.5;
  const double k = k_bisection(2 * kPi / T, d);
  const double r = stokes2_harmonic_ratio(k, d, H);
  EXPECT_NEAR(stokes2_elevation(H, T, d, 0, 0, 0, g), 0.5 * H * (1 + r), 1e-12);
  EXPECT_NEAR(stokes2_elevation(H, T, d, kPi / k, 0, 0, g), -0.5 * H * (1 - r), 1e-12);
  // Deep water: a2/a1 -> k H / 4 (= k a / 2).
  EXPECT_NEAR(stokes2_harmonic_ratio(10.0, 100.0, 0.01), 10.0 * 0.01 / 4, 1e-12);
  EXPECT_NEAR(solitary_elevation(0.05, 0.5, 3.0, 0.0, 3.0, g), 0.05, 1e-15);
}

TEST(WaveTheory, AssessmentRegimesAndWarnings) {
  const PaddleGeometry piston{PaddleGeometry::Type::Piston, 0.0, 0.0};
  // A gentle intermediate-depth wave: linear, no warning.
  auto a = assess_regular_wave(0.01, 1.2, 0.6, piston, 1, 0.0, g);
  EXPECT_EQ(a.theory, "linear (Airy)");
  EXPECT_TRUE(a.warnings.empty());
  EXPECT_NEAR(a.stroke * a.transfer, 0.01, 1e-14);
  EXPECT_NEAR(a.ursell, 0.01 * a.length * a.length / std::pow(0.6, 3), 1e-12);
  // A steeper one needs second order, and says so for first-order generation.
  a = assess_regular_wave(0.1, 1.6, 0.6, piston, 1, 0.0, g);
  EXPECT_EQ(a.theory, "Stokes second order");
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_NE(a.warnings[0].find("order 2"), std::string::npos);
  EXPECT_TRUE(assess_regular_wave(0.1, 1.6, 0.6, piston, 2, 0.0, g).warnings.empty());
  // Long waves in shallow water are cnoidal; over-steep waves break.
  a = assess_regular_wave(0.05, 10.0, 0.3, piston, 1, 0.0, g);
  EXPECT_NE(a.theory.find("cnoidal"), std::string::npos);
  EXPECT_NE(a.depth_regime.find("shallow"), std::string::npos);
  a = assess_regular_wave(0.5, 1.0, 2.0, piston, 1, 0.0, g);
  EXPECT_NE(a.theory.find("breaking"), std::string::npos);
  EXPECT_NE(a.depth_regime.find("deep"), std::string::npos);
  // Resolution warnings with dp.
  a = assess_regular_wave(0.05, 1.6, 0.6, piston, 2, 0.01, g);
  ASSERT_FALSE(a.warnings.empty());
  EXPECT_NE(a.warnings.back().find("H/dp"), std::string::npos);
}

}  // namespace
}  // namespace swell::waves
