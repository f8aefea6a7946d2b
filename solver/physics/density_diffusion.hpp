// Density diffusion as a small value type, in the arithmetic the pair loop uses (T, the
// evaluator's PairReal; the parameters are held in it).
#pragma once

namespace swell {

// drho_a/dt += delta h c0 psi_ab . gradW_ab V_b between fluid particles, with
// psi_ab . gradW_ab = -2 drho_ab (r_ab . gradW_ab) / (r_ab^2 + eta^2).
// Molteni & Colagrossi (2009): drho_ab = rho_b - rho_a.
// Fourtakas et al. (2019): the same on the dynamic density, drho_ab = (rho_b - rho_a) minus its
//   hydrostatic part rho0 g.(x_b - x_a) / c0^2 (their eq. 12, Tait EoS linearised for
//   |dz| <= 2h); with g.(x_b - x_a) = -g.r_ab this is (rho_b - rho_a) + rho0/c0^2 g.r_ab.
template <class T = double>
struct DensityDiffusion {
  T coef;          // delta h c0 (0: off)
  T rho0_over_c2;  // rho0 / c0^2 for Fourtakas, 0 for Molteni-Colagrossi
  // The weight of particle a's sum: -2 coef for a diffusing particle, 0 otherwise.
  T weight(bool diffuses) const { return diffuses ? T(-2.0) * coef : T(0); }
  // drho_ab, with g_dot_rab = g . r_ab.
  T drho(T rho_a, T rho_b, T g_dot_rab) const { return (rho_b - rho_a) + rho0_over_c2 * g_dot_rab; }
  // One pair's contribution: weight_b (1 for a fluid b, 0 for a wall) times weight_a (above)
  // times drho_ab (r.gradW) / (r^2 + eta^2) V_b.
  T term(T weight_b, T weight_a, T drho_ab, T r_dot_gradw, T inv_r2e, T vol_b) const {
    return weight_b * weight_a * drho_ab * r_dot_gradw * inv_r2e * vol_b;
  }
};

}  // namespace swell
