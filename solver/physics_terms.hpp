// Small physics pieces evaluated per particle or per pair. Each is a value type with inline
// methods so the interaction loop (solver/interaction.hpp) is written once and stays readable.
#pragma once

#include <cmath>

namespace swell {

// Tait equation of state, P = B ((rho/rho0)^gamma - 1), B = c0^2 rho0 / gamma (Monaghan 1994),
// for the default gamma = 7 evaluated with multiplications only.
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
  double hydrostatic_density(double g_depth) const {
    return rho0 * std::pow(1.0 + rho0 * g_depth / b, 1.0 / gamma);
  }
};

// Monaghan (1992) artificial viscosity: Pi_ab = -alpha cbar mu_ab / rhobar_ab for approaching
// pairs, mu_ab = h v_ab.r_ab / (r_ab^2 + eta^2). Returns Pi_ab, added to the pressure term.
struct ArtificialViscosity {
  double alpha, h, eta2;
  double pi(double vr, double r2, double cbar, double rhobar) const {
    if (vr >= 0.0) return 0.0;
    const double mu = h * vr / (r2 + eta2);
    return -alpha * cbar * mu / rhobar;
  }
};

// Laminar viscosity of Lo & Shao (2002): dv_a/dt += m_b 4 nu (r_ab . gradW_ab) /
// ((rho_a + rho_b)(r_ab^2 + eta^2)) v_ab. Returns the factor multiplying m_b v_ab.
struct LaminarViscosity {
  double nu, eta2;
  double factor(double r_dot_gradw, double r2, double rho_a, double rho_b) const {
    return 4.0 * nu * r_dot_gradw / ((rho_a + rho_b) * (r2 + eta2));
  }
};

// Density diffusion, fluid-fluid pairs only.
// Molteni & Colagrossi (2009): drho_a += delta h c0 psi_ab . gradW_ab V_b with
//   psi_ab = 2 (rho_b - rho_a) r_ba / (r^2 + eta^2).
// Fourtakas et al. (2019): the same on the dynamic density, rho_b - rho_a minus its hydrostatic
//   part rho0 g.(x_b - x_a) / c0^2 (their eq. 12 with the Tait EoS linearised for |dz| <= 2h).
// Returns the contribution for one pair; r_dot_gradw = r_ab . gradW_ab (negative).
struct DensityDiffusion {
  double coef;          // delta h c0 (0 disables)
  double rho0_over_c2;  // rho0 / c0^2 for the hydrostatic part (0 for Molteni-Colagrossi)
  double drho(double rho_a, double rho_b, double g_dot_xba, double r_dot_gradw, double r2,
              double eta2, double vol_b) const {
    const double drho_dyn = (rho_b - rho_a) - rho0_over_c2 * g_dot_xba;
    // psi_ab . gradW_ab = 2 drho r_ba . gradW_ab / (r^2+eta^2) = -2 drho r_ab.gradW_ab / (...)
    return coef * (-2.0) * drho_dyn * r_dot_gradw / (r2 + eta2) * vol_b;
  }
};

}  // namespace swell
