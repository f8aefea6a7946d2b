// Equations of state as small value types.
#pragma once

#include <cmath>

namespace swell {

// Tait equation of state, P = B ((rho/rho0)^gamma - 1), B = c0^2 rho0 / gamma (Monaghan 1994).
// Any gamma > 1; the default gamma = 7 is evaluated with multiplications only. The pair loop
// reads P/rho^2 and c from per-particle buffers filled by these methods (solver/physics/
// wcsph_forces.hpp), so it makes no assumption on gamma.
struct TaitEos {
  double rho0, c0, gamma, b, inv_rho0;
  TaitEos(double rho0_, double c0_, double gamma_)
      : rho0(rho0_), c0(c0_), gamma(gamma_), b(c0_ * c0_ * rho0_ / gamma_), inv_rho0(1.0 / rho0_) {}

  double pressure(double rho) const {
    const double r = rho * inv_rho0;
    if (gamma == 7.0) {
      const double r2 = r * r, r3 = r2 * r;
      return b * (r3 * r3 * r - 1.0);
    }
    return b * (std::pow(r, gamma) - 1.0);
  }
  // c = sqrt(dP/drho) = c0 (rho/rho0)^((gamma-1)/2)
  double sound_speed(double rho) const {
    const double r = rho * inv_rho0;
    if (gamma == 7.0) return c0 * r * r * r;
    return c0 * std::pow(r, 0.5 * (gamma - 1.0));
  }
  // Density of a fluid at rest at depth d below its free surface: P = rho0 g d inverted.
  double hydrostatic_density(double g_depth) const { return density(rho0 * g_depth); }
  // The density at pressure p (the inverse of pressure(); p > -B).
  double density(double p) const { return rho0 * std::pow(1.0 + p / b, 1.0 / gamma); }
};

}  // namespace swell
