// Viscosity models as small value types, in the arithmetic the pair loop uses (the evaluator
// in wcsph_evaluator.hpp calls these; tests/test_pair_loop.cpp checks them against a
// brute-force sum). inv_r2e = 1 / (r_ab^2 + eta^2), eta^2 = 0.01 h^2.
#pragma once

namespace swell {

// Monaghan (1992) artificial viscosity: Pi_ab = -alpha cbar mu_ab / rhobar_ab for approaching
// pairs (v_ab.r_ab < 0), mu_ab = h v_ab.r_ab / (r_ab^2 + eta^2); Pi_ab is added to the pressure
// term P_a/rho_a^2 + P_b/rho_b^2. mu() is also the viscous time-step signal (Monaghan & Kos 1999).
struct ArtificialViscosity {
  double alpha, h;
  // mu_ab for approaching pairs, 0 otherwise (a select, not a branch, in the SIMD loop).
  double mu(double vr, double inv_r2e) const { return vr < 0.0 ? h * vr * inv_r2e : 0.0; }
  double pi(double mu, double cs_a, double cs_b, double rho_a, double rho_b) const {
    return -alpha * (0.5 * (cs_a + cs_b)) * mu / (0.5 * (rho_a + rho_b));
  }
};

// Laminar viscosity of Lo & Shao (2002): dv_a/dt += m_b 4 nu (r_ab . gradW_ab) /
// ((rho_a + rho_b)(r_ab^2 + eta^2)) v_ab. factor() returns the coefficient of v_ab;
// r_dot_gradw = r_ab . gradW_ab.
struct LaminarViscosity {
  double nu4;  // 4 nu
  double factor(double m_b, double r_dot_gradw, double rho_a, double rho_b, double inv_r2e) const {
    return m_b * nu4 * r_dot_gradw / (rho_a + rho_b) * inv_r2e;
  }
};

}  // namespace swell
