#include "waves/wavemaker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "waves/theory.hpp"

namespace swell::waves {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Solves X = A tanh(kappa (c tau - X)) for X (Newton; F(X) = X - A tanh(u) has F' >= 1).
double goring_position(const SolitaryPaddle& s, double tau, double& sech2) {
  const double a = 0.5 * s.stroke;
  double x = 0.0;
  for (int it = 0; it < 100; ++it) {
    const double u = s.kappa * (s.celerity * tau - x);
    const double th = std::tanh(u);
    const double f = x - a * th;
    const double df = 1.0 + a * s.kappa * (1.0 - th * th);
    const double step = f / df;
    x -= step;
    if (std::abs(step) <= 1e-15 * (a + std::abs(x))) break;
  }
  const double th = std::tanh(s.kappa * (s.celerity * tau - x));
  sech2 = 1.0 - th * th;
  return x;
}

// sum over pairs i < j of the first n components of coef[p(i, j)] term(i, j, s_i, c_i, s_j,
// c_j), s = sin(angle), c = cos(angle), in blocks whose sines live on the stack: n sines per
// block row, no allocation.
template <class Angle, class Term>
double pair_sum(std::size_t n, const std::vector<double>& coef, Angle angle, Term term) {
  constexpr std::size_t kBlock = 128;
  double si[kBlock], ci[kBlock], sj[kBlock], cj[kBlock];
  double total = 0.0;
  for (std::size_t i0 = 0; i0 < n; i0 += kBlock) {
    const std::size_t ni = std::min(kBlock, n - i0);
    for (std::size_t a = 0; a < ni; ++a) {
      const double x = angle(i0 + a);
      si[a] = std::sin(x);
      ci[a] = std::cos(x);
    }
    for (std::size_t j0 = i0; j0 < n; j0 += kBlock) {
      const std::size_t nj = std::min(kBlock, n - j0);
      const double* sb = si;
      const double* cb = ci;
      if (j0 != i0) {
        for (std::size_t b = 0; b < nj; ++b) {
          const double x = angle(j0 + b);
          sj[b] = std::sin(x);
          cj[b] = std::cos(x);
        }
        sb = sj;
        cb = cj;
      }
      for (std::size_t a = 0; a < ni; ++a) {
        const std::size_t i = i0 + a;
        // p(i, j) = row + j; for i = 0 the unsigned wrap of row = -1 is undone by + j (j >= 1).
        const std::size_t row = i * n - i * (i + 1) / 2 - i - 1;
        for (std::size_t b = (j0 == i0 ? a + 1 : 0); b < nj; ++b) {
          const std::size_t j = j0 + b;
          total += coef[row + j] * term(i, j, si[a], ci[a], sb[b], cb[b]);
        }
      }
    }
  }
  return total;
}

}  // namespace

double transfer_function(const PaddleGeometry& paddle, double k) {
  const double d = paddle.depth;
  if (!(d > 0.0) || !(k > 0.0))
    throw std::invalid_argument("wavemaker: depth and wave number must be > 0 (depth " + num(d) +
                                " m, k " + num(k) + " rad/m)");
  const double kd = k * d;
  const double l = paddle.hinge_height;
  const bool piston = paddle.type == PaddleGeometry::Type::Piston;
  if (!piston && !(l < d))
    throw std::invalid_argument("wavemaker: the flap hinge (" + num(l) +
                                " m above the bed) must be below the still-water level (" + num(d) +
                                " m)");
  // Deep water (sinh 2kd would overflow): the limits 2 and 2 (1 - 1 / (k (d - l))), exact to
  // double precision there.
  if (kd > 350.0) return piston ? 2.0 : 2.0 * (1.0 - 1.0 / (k * (d - l)));
  const double denom = std::sinh(2.0 * kd) + 2.0 * kd;
  if (piston) return 2.0 * (std::cosh(2.0 * kd) - 1.0) / denom;
  // f(s) = (s - l) / (d - l) on s = z + d in [max(l, 0), d]:
  // I = [(s - l) sinh(ks) / k - cosh(ks) / k^2]_{s0}^{d} / (d - l).
  const double s0 = std::max(l, 0.0);
  const double upper = (d - l) * std::sinh(kd) / k - std::cosh(kd) / (k * k);
  const double lower = (s0 - l) * std::sinh(k * s0) / k - std::cosh(k * s0) / (k * k);
  const double integral = (upper - lower) / (d - l);
  return 4.0 * k * std::sinh(kd) * integral / denom;
}

SolitaryPaddle make_solitary_paddle(double height, double depth, double g) {
  if (!(depth > 0.0) || !(height > 0.0) || !(g > 0.0))
    throw std::invalid_argument("solitary wave: height, depth and g must be > 0 (H " + num(height) +
                                " m, d " + num(depth) + " m)");
  SolitaryPaddle s;
  s.height = height;
  s.depth = depth;
  s.g = g;
  s.kappa = std::sqrt(3.0 * height / (4.0 * depth * depth * depth));
  s.celerity = std::sqrt(g * (depth + height));
  s.stroke = 2.0 * height / (s.kappa * depth);
  s.duration = 2.0 * (3.8 + height / depth) / (s.kappa * s.celerity);
  double sech2 = 0.0;
  s.start = goring_position(s, -0.5 * s.duration, sech2);
  return s;
}

double PaddleSignal::displacement(double t) const {
  if (solitary) {
    const double tau = std::clamp(t, 0.0, soliton.duration) - 0.5 * soliton.duration;
    double sech2 = 0.0;
    return goring_position(soliton, tau, sech2) - soliton.start;  // starts at exactly 0
  }
  double x = 0.0;
  for (const auto& c : components) x += c.amplitude * std::sin(c.omega * t + c.phase);
  if (pair_components > 1) {
    x += pair_sum(
        pair_components, pair_paddle,
        [&](std::size_t i) { return components[i].omega * t + components[i].phase; },
        [](std::size_t, std::size_t, double s1, double c1, double s2, double c2) {
          return s1 * c2 - c1 * s2;  // sin(psi_i - psi_j)
        });
  }
  return x;
}

double PaddleSignal::velocity(double t) const {
  if (solitary) {
    if (t <= 0.0 || t >= soliton.duration) return 0.0;
    double sech2 = 0.0;
    goring_position(soliton, t - 0.5 * soliton.duration, sech2);
    const double ak = 0.5 * soliton.stroke * soliton.kappa;  // = H / d
    return ak * soliton.celerity * sech2 / (1.0 + ak * sech2);
  }
  double v = 0.0;
  for (const auto& c : components) v += c.amplitude * c.omega * std::cos(c.omega * t + c.phase);
  if (pair_components > 1) {
    v += pair_sum(
        pair_components, pair_paddle,
        [&](std::size_t i) { return components[i].omega * t + components[i].phase; },
        [&](std::size_t i, std::size_t j, double s1, double c1, double s2, double c2) {
          return (components[i].omega - components[j].omega) * (c1 * c2 + s1 * s2);
        });
  }
  return v;
}

double PaddleSignal::shortest_period() const {
  if (solitary) return soliton.duration;
  double w = 0.0;
  for (const auto& c : components) w = std::max(w, c.omega);
  return w > 0.0 ? 2.0 * std::numbers::pi / w : 0.0;
}

double PaddleSignal::amplitude_bound() const {
  if (solitary) return soliton.stroke;
  double a = 0.0;
  for (const auto& c : components) a += std::abs(c.amplitude);
  for (const double c : pair_paddle) a += std::abs(c);
  return a;
}

double PaddleSignal::elevation(double t, double x) const {
  if (solitary) {
    // Goring's trajectory is centred: the crest is at xi = c tau, tau = t - duration / 2, and a
    // point x from the paddle's rest position is at xi = x + start.
    const double u =
        soliton.kappa * (soliton.celerity * (t - 0.5 * soliton.duration) - (x + soliton.start));
    const double sech = 1.0 / std::cosh(u);
    return soliton.height * sech * sech;
  }
  double eta = 0.0;
  for (const auto& c : target) eta += c.amplitude * std::cos(c.omega * t + c.phase - c.k * x);
  if (bound_second_harmonic != 0.0 && !target.empty()) {
    const auto& c = target.front();
    eta += bound_second_harmonic * std::cos(2.0 * (c.omega * t + c.phase - c.k * x));
  }
  if (pair_components > 1) {
    eta += pair_sum(
        pair_components, pair_surface,
        [&](std::size_t i) { return target[i].omega * t + target[i].phase - target[i].k * x; },
        [](std::size_t, std::size_t, double s1, double c1, double s2, double c2) {
          return c1 * c2 + s1 * s2;  // cos(theta_i - theta_j)
        });
  }
  return eta;
}

double PaddleSignal::peak_omega() const {
  double best = 0.0, omega = 0.0;
  for (const auto& c : target)
    if (std::abs(c.amplitude) > best) {
      best = std::abs(c.amplitude);
      omega = c.omega;
    }
  return omega;
}

PaddleSignal regular_paddle(const PaddleGeometry& paddle, double height, double period, int order,
                            double phase, double g) {
  if (!(height > 0.0) || !(period > 0.0))
    throw std::invalid_argument("regular wave: height and period must be > 0 (H " + num(height) +
                                " m, T " + num(period) + " s)");
  if (order != 1 && order != 2)
    throw std::invalid_argument("regular wave: order must be 1 or 2, got " + std::to_string(order));
  if (order == 2 && paddle.type != PaddleGeometry::Type::Piston)
    throw std::invalid_argument(
        "regular wave: second-order generation is implemented for pistons only (use order 1 "
        "with a flap)");
  const double omega = 2.0 * std::numbers::pi / period;
  const double k = wave_number(omega, paddle.depth, g);
  const double f = transfer_function(paddle, k);
  PaddleSignal s;
  s.paddle = paddle;
  s.components.push_back({0.5 * height / f, omega, phase});
  s.target.push_back({0.5 * height, omega, phase, k});
  if (order == 2) {
    s.bound_second_harmonic = 0.5 * height * stokes2_harmonic_ratio(k, paddle.depth, height);
    const double kd = k * paddle.depth, sh = std::sinh(kd);
    const double a2 =
        height * height / (32.0 * paddle.depth) * (3.0 * std::cosh(kd) / (sh * sh * sh) - 2.0 / f);
    s.components.push_back({a2, 2.0 * omega, 2.0 * phase});
  }
  return s;
}

PaddleSignal solitary_paddle(const PaddleGeometry& paddle, double height, double g) {
  if (paddle.type != PaddleGeometry::Type::Piston)
    throw std::invalid_argument("solitary wave: Goring's trajectory is for a piston paddle");
  PaddleSignal s;
  s.paddle = paddle;
  s.solitary = true;
  s.soliton = make_solitary_paddle(height, paddle.depth, g);
  return s;
}

PaddleSignal linear_paddle(const PaddleGeometry& paddle,
                           const std::vector<SurfaceComponent>& surface, double g) {
  PaddleSignal s;
  s.paddle = paddle;
  s.components.reserve(surface.size());
  for (const auto& c : surface) {
    if (!(c.omega > 0.0))
      throw std::invalid_argument("wave component: angular frequency must be > 0");
    const double k = wave_number(c.omega, paddle.depth, g);
    s.components.push_back({c.amplitude / transfer_function(paddle, k), c.omega, c.phase});
    s.target.push_back({c.amplitude, c.omega, c.phase, k});
  }
  return s;
}

PaddleSignal second_order_paddle(const PaddleGeometry& paddle,
                                 const std::vector<SurfaceComponent>& surface, double g) {
  if (paddle.type != PaddleGeometry::Type::Piston)
    throw std::invalid_argument(
        "second-order generation of a component set is implemented for pistons only (use "
        "order 1 with a flap)");
  PaddleSignal s = linear_paddle(paddle, surface, g);
  const std::size_t n = surface.size();
  if (n < 2) return s;
  s.pair_components = n;
  s.pair_paddle.reserve(n * (n - 1) / 2);
  s.pair_surface.reserve(n * (n - 1) / 2);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const auto& a = s.target[i];
      const auto& b = s.target[j];
      if (a.omega == b.omega)
        throw std::invalid_argument("second-order generation: components " + std::to_string(i) +
                                    " and " + std::to_string(j) + " share the frequency " +
                                    num(a.omega) + " rad/s");
      const double aa = a.amplitude * b.amplitude;
      s.pair_paddle.push_back(aa * subharmonic_piston(a.omega, a.k, b.omega, b.k, paddle.depth, g));
      s.pair_surface.push_back(
          aa * second_order_kernel(a.omega, a.k, b.omega, b.k, paddle.depth, false, g));
    }
  return s;
}

double linear_elevation(const std::vector<SurfaceComponent>& surface, double depth, double x,
                        double t, double g) {
  double eta = 0.0;
  for (const auto& c : surface)
    eta += c.amplitude * std::cos(c.omega * t + c.phase - wave_number(c.omega, depth, g) * x);
  return eta;
}

}  // namespace swell::waves
