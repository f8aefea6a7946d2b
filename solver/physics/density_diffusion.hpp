// Density diffusion as a small value type, in the arithmetic the pair loop uses.
#pragma once

namespace swell {

// drho_a/dt += delta h c0 psi_ab . gradW_ab V_b between fluid particles, with
// psi_ab . gradW_ab = -2 drho_ab (r_ab . gradW_ab) / (r_ab^2 + eta^2).
// Molteni & Colagrossi (2009): drho_ab = rho_b - rho_a.
// Fourtakas et al. (2019): the same on the dynamic density, drho_ab = (rho_b - rho_a) minus its
//   hydrostatic part rho0 g.(x_b - x_a) / c0^2 (their eq. 12, Tait EoS linearised for
//   |dz| <= 2h); with g.(x_b - x_a) = -g.r_ab this is (rho_b - rho_a) + rho0/c0^2 g.r_ab.
struct DensityDiffusion {
  double coef;          // delta h c0 (0: off)
  double rho0_over_c2;  // rho0 / c0^2 for Fourtakas, 0 for Molteni-Colagrossi
  // The weight of particle a's sum: -2 coef for a diffusing particle, 0 otherwise.
  double weight(bool diffuses) const { return diffuses ? -2.0 * coef : 0.0; }
  // drho_ab, with g_dot_rab = g . r_ab.
  double drho(double rho_a, double rho_b, double g_dot_rab) const {
    return (rho_b - rho_a) + rho0_over_c2 * g_dot_rab;
  }
  // One pair's contribution: weight_b (1 for a fluid b, 0 for a wall) times weight_a (above)
  // times drho_ab (r.gradW) / (r^2 + eta^2) V_b.
  double term(double weight_b, double weight_a, double drho_ab, double r_dot_gradw, double inv_r2e,
              double vol_b) const {
    return weight_b * weight_a * drho_ab * r_dot_gradw * inv_r2e * vol_b;
  }
};

}  // namespace swell
