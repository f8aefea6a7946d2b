// Viscosity models as small value types, in the arithmetic the pair loop uses (the evaluator
// in wcsph_evaluator.hpp calls these; tests/test_pair_loop.cpp checks them against a
// brute-force sum). inv_r2e = 1 / (r_ab^2 + eta^2), eta^2 = 0.01 h^2. T: the arithmetic type
// (the evaluator's PairReal); the parameters are held in it, rounded once when built.
#pragma once

namespace swell {

// Monaghan (1992) artificial viscosity: Pi_ab = -alpha cbar mu_ab / rhobar_ab for approaching
// pairs (v_ab.r_ab < 0), mu_ab = h v_ab.r_ab / (r_ab^2 + eta^2); Pi_ab is added to the pressure
// term P_a/rho_a^2 + P_b/rho_b^2. mu() is also the viscous time-step signal (Monaghan & Kos 1999).
template <class T = double>
struct ArtificialViscosity {
  T alpha, h;
  // mu_ab for approaching pairs, 0 otherwise (a select, not a branch, in the SIMD loop).
  T mu(T vr, T inv_r2e) const { return vr < T(0) ? h * vr * inv_r2e : T(0); }
  T pi(T mu, T cs_a, T cs_b, T rho_a, T rho_b) const {
    return -alpha * (T(0.5) * (cs_a + cs_b)) * mu / (T(0.5) * (rho_a + rho_b));
  }
};

// Laminar viscosity of Lo & Shao (2002): dv_a/dt += m_b 4 nu (r_ab . gradW_ab) /
// ((rho_a + rho_b)(r_ab^2 + eta^2)) v_ab. factor() returns the coefficient of v_ab;
// r_dot_gradw = r_ab . gradW_ab.
template <class T = double>
struct LaminarViscosity {
  T nu4;  // 4 nu
  T factor(T m_b, T r_dot_gradw, T rho_a, T rho_b, T inv_r2e) const {
    return m_b * nu4 * r_dot_gradw / (rho_a + rho_b) * inv_r2e;
  }
};

}  // namespace swell
