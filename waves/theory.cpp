#include "waves/theory.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace swell::waves {

namespace {

std::string fmt(const char* format, double a, double b = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b);
  return buf;
}

}  // namespace

double stokes2_harmonic_ratio(double k, double depth, double height) {
  const double kd = k * depth;
  if (kd > 350.0) return k * height / 8.0 * 2.0;  // cosh kd cosh 2kd / sinh^3 kd -> 2
  const double sh = std::sinh(kd);
  return k * height / 8.0 * std::cosh(kd) * (2.0 + std::cosh(2.0 * kd)) / (sh * sh * sh);
}

double stokes2_elevation(double height, double period, double depth, double x, double t,
                         double phase, double g) {
  const double omega = 2.0 * std::numbers::pi / period;
  const double k = wave_number(omega, depth, g);
  const double theta = k * x - omega * t + phase;
  const double a1 = 0.5 * height;
  return a1 * std::cos(theta) +
         a1 * stokes2_harmonic_ratio(k, depth, height) * std::cos(2.0 * theta);
}

double solitary_elevation(double height, double depth, double x, double t, double x0, double g) {
  const SolitaryPaddle s = make_solitary_paddle(height, depth, g);
  const double ch = std::cosh(s.kappa * (x - x0 - s.celerity * t));
  return height / (ch * ch);
}

namespace {

struct PairTerms {
  double w, k, q, r, b;  // W, K, Q, R, B of theory.hpp
};

PairTerms pair_terms(double wi, double ki, double wj, double kj, double d, bool sum, double g) {
  if (!(wi > 0.0 && wj > 0.0 && ki > 0.0 && kj > 0.0 && d > 0.0))
    throw std::invalid_argument(
        "second-order pair: frequencies, wave numbers and depth must be > 0");
  const double s = sum ? 1.0 : -1.0;
  PairTerms p;
  p.w = wi + s * wj;
  p.k = ki + s * kj;
  if (!sum && p.w == 0.0)
    throw std::invalid_argument(
        "second-order pair: two components of the same frequency have no difference term");
  p.q = g * g * ki * kj / (wi * wj);
  const double ei = (g * g * ki * ki - wi * wi * wi * wi) / wi;
  const double ej = (g * g * kj * kj - wj * wj * wj * wj) / wj;
  p.r = -p.w * (p.q - s * wi * wj) - 0.5 * (ei + s * ej);
  // g K tanh(K d) is even in K; |K d| > 350 would overflow nothing (tanh saturates).
  p.b = p.r / (g * p.k * std::tanh(p.k * d) - p.w * p.w);
  return p;
}

}  // namespace

double second_order_kernel(double wi, double ki, double wj, double kj, double d, bool sum,
                           double g) {
  const PairTerms p = pair_terms(wi, ki, wj, kj, d, sum, g);
  const double s = sum ? 1.0 : -1.0;
  return (p.w * p.b - 0.5 * (p.q - s * wi * wj - wi * wi - wj * wj)) / g;
}

double subharmonic_flux(double wi, double ki, double wj, double kj, double d, double g) {
  const PairTerms p = pair_terms(wi, ki, wj, kj, d, false, g);
  return p.b * std::tanh(p.k * d) + 0.5 * (g * ki / wi + g * kj / wj);
}

double subharmonic_piston(double wi, double ki, double wj, double kj, double d, double g) {
  const double kdiff = ki - kj;
  if (kdiff == 0.0)
    throw std::invalid_argument(
        "second-order pair: two components of the same frequency have no difference term");
  const PaddleGeometry piston{PaddleGeometry::Type::Piston, d, 0.0};
  const double fi = transfer_function(piston, ki), fj = transfer_function(piston, kj);
  return second_order_kernel(wi, ki, wj, kj, d, false, g) / (kdiff * d) -
         (1.0 / fi - 1.0 / fj) / (2.0 * d);
}

WaveAssessment assess_regular_wave(double height, double period, double depth,
                                   const PaddleGeometry& paddle, int order, double dp, double g) {
  if (!(height > 0.0) || !(period > 0.0) || !(depth > 0.0))
    throw std::invalid_argument("waves: H, T and d must be numbers > 0");
  WaveAssessment a;
  a.height = height;
  a.period = period;
  a.depth = depth;
  const double omega = 2.0 * std::numbers::pi / period;
  a.k = wave_number(omega, depth, g);
  a.length = 2.0 * std::numbers::pi / a.k;
  a.kd = a.k * depth;
  a.celerity = omega / a.k;
  a.group_celerity = group_ratio(a.kd) * a.celerity;
  a.steepness = height / a.length;
  a.ursell = height * a.length * a.length / (depth * depth * depth);
  a.relative_depth = depth / a.length;
  a.d_gt2 = depth / (g * period * period);
  a.h_gt2 = height / (g * period * period);
  a.breaking_height = 0.142 * a.length * std::tanh(a.kd);
  a.harmonic_ratio = stokes2_harmonic_ratio(a.k, depth, height);
  a.depth_regime = a.relative_depth < 0.05  ? "shallow water (d/L < 1/20)"
                   : a.relative_depth > 0.5 ? "deep water (d/L > 1/2)"
                                            : "intermediate depth (1/20 <= d/L <= 1/2)";
  PaddleGeometry p = paddle;
  p.depth = depth;
  a.transfer = transfer_function(p, a.k);
  a.stroke = height / a.transfer;
  if (p.type == PaddleGeometry::Type::Piston) {
    const PaddleSignal s = regular_paddle(p, height, period, 2, 0.0, g);
    a.stroke2 = s.components[1].amplitude;
  }

  const bool breaking = height >= a.breaking_height;
  const bool cnoidal = a.ursell > 26.0;
  if (breaking) {
    a.theory = "breaking (H exceeds the Miche limit)";
    a.warnings.push_back(
        fmt("H = %.4g m is at or above the Miche breaking limit %.4g m: the wave "
            "breaks at the paddle; no regular-wave theory applies",
            height, a.breaking_height));
  } else if (cnoidal) {
    a.theory = "cnoidal / stream function (Ursell number > 26)";
    a.warnings.push_back(
        fmt("Ursell number %.3g > 26: a cnoidal wave; Stokes theories and a "
            "Stokes paddle signal (first or second order) are outside their "
            "validity and will shed free harmonics",
            a.ursell));
  } else if (a.harmonic_ratio >= 0.25) {
    a.theory = "Stokes higher order (a2/a1 >= 1/4)";
    a.warnings.push_back(
        fmt("a2/a1 = %.3f >= 1/4: Stokes second order predicts a secondary "
            "crest; a higher-order theory (Stokes V, stream function) is needed",
            a.harmonic_ratio));
  } else if (a.harmonic_ratio >= 0.02) {
    a.theory = "Stokes second order";
    if (order == 1)
      a.warnings.push_back(
          fmt("a2/a1 = %.3f: second-order effects are %.0f %% of the first "
              "harmonic; first-order generation will make a spurious free "
              "second harmonic (use order 2)",
              a.harmonic_ratio, 100.0 * a.harmonic_ratio));
  } else {
    a.theory = "linear (Airy)";
  }
  if (order == 2 && p.type != PaddleGeometry::Type::Piston)
    a.warnings.push_back("second-order generation is implemented for pistons only");
  if (dp > 0.0) {
    if (height / dp < 10.0)
      a.warnings.push_back(
          fmt("H/dp = %.3g < 10: the wave height is resolved by fewer than 10 "
              "particles; expect strong numerical decay",
              height / dp));
    if (a.length / dp < 50.0)
      a.warnings.push_back(
          fmt("L/dp = %.3g < 50: the wave length is poorly resolved", a.length / dp));
  }
  return a;
}

}  // namespace swell::waves
