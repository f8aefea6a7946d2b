// Ideal-gas equation of state for the compressible path (a value type, like TaitEos).
#pragma once

#include <cmath>

namespace swell::compressible {

// P = (gamma - 1) rho u with u the specific internal energy; c = sqrt(gamma P / rho).
struct IdealGas {
  double gamma = 1.4;

  double pressure(double rho, double u) const { return (gamma - 1.0) * rho * u; }
  double sound_speed(double rho, double u) const {
    return std::sqrt(gamma * (gamma - 1.0) * u);  // = sqrt(gamma P / rho)
  }
  double internal_energy(double rho, double p) const { return p / ((gamma - 1.0) * rho); }
};

}  // namespace swell::compressible
