#include "waves/dispersion.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace swell::waves {

namespace {

void check_positive(double v, const char* what) {
  if (!(v > 0.0) || !std::isfinite(v))
    throw std::invalid_argument(std::string("waves: ") + what +
                                " must be a finite number > 0 (got " + std::to_string(v) + ")");
}

}  // namespace

double wave_number(double omega, double depth, double g) {
  check_positive(omega, "the angular frequency");
  check_positive(depth, "the depth");
  check_positive(g, "gravity");
  const double k0 = omega * omega / g;  // deep-water wave number
  const double k0d = k0 * depth;
  // Fenton & McKee (1990): k d ~ k0 d / tanh((k0 d)^(3/4))^(2/3), within 1.5 % everywhere.
  double k = k0 / std::pow(std::tanh(std::pow(k0d, 0.75)), 2.0 / 3.0);
  if (!std::isfinite(k) || k <= 0.0) k = std::max(k0, omega / std::sqrt(g * depth));
  for (int it = 0; it < 50; ++it) {
    const double th = std::tanh(k * depth);
    const double f = g * k * th - omega * omega;
    const double df = g * th + g * k * depth * (1.0 - th * th);
    const double step = f / df;
    k -= step;
    if (std::abs(step) <= 1e-15 * k) break;
  }
  return k;
}

double wave_length(double period, double depth, double g) {
  check_positive(period, "the wave period");
  return 2.0 * std::numbers::pi / wave_number(2.0 * std::numbers::pi / period, depth, g);
}

double phase_speed(double omega, double depth, double g) {
  return omega / wave_number(omega, depth, g);
}

double group_ratio(double kd) {
  if (kd > 350.0) return 0.5;  // sinh overflows; 2kd / sinh 2kd is 0 to double precision
  if (kd < 1e-8) return 1.0;
  return 0.5 * (1.0 + 2.0 * kd / std::sinh(2.0 * kd));
}

double group_speed(double omega, double depth, double g) {
  const double k = wave_number(omega, depth, g);
  return group_ratio(k * depth) * omega / k;
}

}  // namespace swell::waves
