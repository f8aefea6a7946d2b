// SPH smoothing kernels as small value types.
//
// Each kernel is built for a fixed smoothing length h and exposes
//   w(r)  - the kernel value W(r, h),
//   f(r)  - (1/r) dW/dr, so that grad_a W_ab = r_ab * f(|r_ab|) with r_ab = x_a - x_b,
//   support() - the radius beyond which W and its gradient vanish (kSupport * h).
// f(r) is finite at r = 0 for every kernel here, so no pair needs a special case.
#pragma once

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace swell {

// Wendland (1995) C2 kernel, W = a_D (1 - q/2)^4 (2q + 1), q = r/h in [0, 2].
// a_1 = 3/(4h), a_2 = 7/(4 pi h^2), a_3 = 21/(16 pi h^3) (normalisation integrals in closed form).
template <int D>
struct WendlandC2 {
  static constexpr double kSupport = 2.0;
  static constexpr const char* kName = "wendland";
  double h, inv_h, a;

  explicit WendlandC2(double h_) : h(h_), inv_h(1.0 / h_), a(norm(h_)) {}

  static double norm(double h) {
    constexpr double pi = std::numbers::pi;
    if constexpr (D == 1) return 3.0 / (4.0 * h);
    if constexpr (D == 2) return 7.0 / (4.0 * pi * h * h);
    return 21.0 / (16.0 * pi * h * h * h);
  }
  double support() const { return kSupport * h; }

  double w(double r) const {
    const double q = r * inv_h;
    if (q >= 2.0) return 0.0;
    const double t = 1.0 - 0.5 * q;
    const double t2 = t * t;
    return a * t2 * t2 * (2.0 * q + 1.0);
  }
  // dW/dr = -5 a q (1 - q/2)^3 / h, so (1/r) dW/dr = -5 a (1 - q/2)^3 / h^2.
  double f(double r) const {
    const double q = r * inv_h;
    if (q >= 2.0) return 0.0;
    const double t = 1.0 - 0.5 * q;
    return -5.0 * a * t * t * t * inv_h * inv_h;
  }
  // f(r) for 0 < r < support(), without branches (the pair loop's SIMD form).
  // T: the pair loop's arithmetic type (PairReal); the parameters are rounded to it.
  template <class T>
  T fs(T r) const {
    const T t = T(1) - T(0.5) * r * T(inv_h);
    return T(-5.0) * T(a) * t * t * t * T(inv_h) * T(inv_h);
  }
  // dW/dh at fixed r (the grad-h term of variable-h SPH). W = h^-D g(r/h) gives
  // dW/dh = -(D W + q dW/dq) / h = -(D w(r) + r^2 f(r)) / h.
  double dwdh(double r) const { return -(D * w(r) + r * r * f(r)) * inv_h; }
};

// Cubic B-spline (Monaghan & Lattanzio 1985), support 2h.
template <int D>
struct CubicSpline {
  static constexpr double kSupport = 2.0;
  static constexpr const char* kName = "cubic";
  double h, inv_h, a;

  explicit CubicSpline(double h_) : h(h_), inv_h(1.0 / h_), a(norm(h_)) {}

  static double norm(double h) {
    constexpr double pi = std::numbers::pi;
    if constexpr (D == 1) return 2.0 / (3.0 * h);
    if constexpr (D == 2) return 10.0 / (7.0 * pi * h * h);
    return 1.0 / (pi * h * h * h);
  }
  double support() const { return kSupport * h; }

  double w(double r) const {
    const double q = r * inv_h;
    if (q >= 2.0) return 0.0;
    if (q < 1.0) return a * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
    const double t = 2.0 - q;
    return a * 0.25 * t * t * t;
  }
  double f(double r) const {
    const double q = r * inv_h;
    if (q >= 2.0) return 0.0;
    // dW/dq = a(-3q + 9/4 q^2) for q < 1, -3/4 a (2-q)^2 otherwise; f = dW/dq / (h^2 q).
    if (q < 1.0) return a * (-3.0 + 2.25 * q) * inv_h * inv_h;
    const double t = 2.0 - q;
    return -0.75 * a * t * t * inv_h * inv_h / q;
  }
  template <class T>
  T fs(T r) const {
    const T q = r * T(inv_h), t = T(2) - q;
    const T inner = T(-3.0) + T(2.25) * q, outer = T(-0.75) * t * t / q;
    return T(a) * (q < T(1) ? inner : outer) * T(inv_h) * T(inv_h);
  }
  // dW/dh at fixed r, as WendlandC2::dwdh (the grad-h term; Price 2012, JCP 231:759, eq. 31).
  double dwdh(double r) const { return -(D * w(r) + r * r * f(r)) * inv_h; }
};

// Quintic spline (Morris, Fox & Zhu 1997), support 3h.
template <int D>
struct QuinticSpline {
  static constexpr double kSupport = 3.0;
  static constexpr const char* kName = "quintic";
  double h, inv_h, a;

  explicit QuinticSpline(double h_) : h(h_), inv_h(1.0 / h_), a(norm(h_)) {}

  static double norm(double h) {
    constexpr double pi = std::numbers::pi;
    if constexpr (D == 1) return 1.0 / (120.0 * h);
    if constexpr (D == 2) return 7.0 / (478.0 * pi * h * h);
    return 1.0 / (120.0 * pi * h * h * h);  // the often-quoted 3/(359 pi) is a misprint
  }
  double support() const { return kSupport * h; }

  static double p5(double x) { return x > 0.0 ? x * x * x * x * x : 0.0; }
  template <class T>
  static T p4(T x) {
    return x > T(0) ? x * x * x * x : T(0);
  }

  double w(double r) const {
    const double q = r * inv_h;
    if (q >= 3.0) return 0.0;
    return a * (p5(3.0 - q) - 6.0 * p5(2.0 - q) + 15.0 * p5(1.0 - q));
  }
  double f(double r) const {
    const double q = r * inv_h;
    if (q >= 3.0) return 0.0;
    if (q < 1e-12) {
      // Limit q -> 0 of (dW/dq)/q is d2W/dq2 at 0 = 20 a (27 - 6*8 + 15) = -120 a.
      return -120.0 * a * inv_h * inv_h;
    }
    const double dwdq = -5.0 * (p4(3.0 - q) - 6.0 * p4(2.0 - q) + 15.0 * p4(1.0 - q));
    return a * dwdq * inv_h * inv_h / q;
  }
  template <class T>
  T fs(T r) const {  // r > 0 (the pair loop drops coincident pairs)
    const T q = r * T(inv_h);
    const T dwdq = T(-5.0) * (p4(T(3) - q) - T(6) * p4(T(2) - q) + T(15) * p4(T(1) - q));
    return T(a) * dwdq * T(inv_h) * T(inv_h) / q;
  }
};

// Gaussian kernel truncated at 3h and renormalised so the truncated kernel integrates to 1.
template <int D>
struct Gaussian {
  static constexpr double kSupport = 3.0;
  static constexpr const char* kName = "gaussian";
  double h, inv_h, a;

  explicit Gaussian(double h_) : h(h_), inv_h(1.0 / h_), a(norm(h_)) {}

  static double norm(double h) {
    constexpr double pi = std::numbers::pi;
    // Mass of exp(-q^2)/(pi^{D/2}) inside q < 3 (radial integrals in closed form).
    double inside;
    if constexpr (D == 1) inside = std::erf(3.0);
    if constexpr (D == 2) inside = 1.0 - std::exp(-9.0);
    if constexpr (D == 3) inside = std::erf(3.0) - 6.0 / std::sqrt(pi) * std::exp(-9.0);
    return 1.0 / (std::pow(pi, 0.5 * D) * std::pow(h, D) * inside);
  }
  double support() const { return kSupport * h; }

  double w(double r) const {
    const double q = r * inv_h;
    if (q >= 3.0) return 0.0;
    return a * std::exp(-q * q);
  }
  double f(double r) const {
    const double q = r * inv_h;
    if (q >= 3.0) return 0.0;
    return -2.0 * a * std::exp(-q * q) * inv_h * inv_h;
  }
  template <class T>
  T fs(T r) const {
    const T q = r * T(inv_h);
    return T(-2.0) * T(a) * std::exp(-q * q) * T(inv_h) * T(inv_h);
  }
};

enum class KernelType { Wendland, Cubic, Quintic, Gaussian };

inline KernelType kernel_from_name(const std::string& name) {
  if (name == "wendland") return KernelType::Wendland;
  if (name == "cubic") return KernelType::Cubic;
  if (name == "quintic") return KernelType::Quintic;
  if (name == "gaussian") return KernelType::Gaussian;
  throw std::invalid_argument("unknown kernel '" + name +
                              "' (expected wendland, cubic, quintic or gaussian)");
}

inline double kernel_support_factor(KernelType k) {
  return (k == KernelType::Quintic || k == KernelType::Gaussian) ? 3.0 : 2.0;
}

// Calls fn(kernel) with the kernel object of the requested type: the one place where the
// runtime kernel choice becomes a compile-time type.
template <int D, class Fn>
decltype(auto) with_kernel(KernelType type, double h, Fn&& fn) {
  switch (type) {
    case KernelType::Cubic:
      return fn(CubicSpline<D>(h));
    case KernelType::Quintic:
      return fn(QuinticSpline<D>(h));
    case KernelType::Gaussian:
      return fn(Gaussian<D>(h));
    case KernelType::Wendland:
    default:
      return fn(WendlandC2<D>(h));
  }
}

}  // namespace swell
