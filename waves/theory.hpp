// Regular-wave theory for checking and planning: surface elevations (linear, Stokes second
// order, solitary) and the validity assessment `swell waves H T d` prints.
#pragma once

#include <string>
#include <vector>

#include "waves/wavemaker.hpp"

namespace swell::waves {

// Stokes second-order elevation of a wave of height H, period T in depth d travelling towards
// +x, theta = k x - w t + phi (Dean & Dalrymple 1991, eq. 11.29):
//   eta = H/2 cos theta + (pi H^2 / (8 L)) cosh kd (2 + cosh 2kd) / sinh^3 kd cos 2 theta.
double stokes2_elevation(double height, double period, double depth, double x, double t,
                         double phase = 0.0, double g = kStandardGravity);

// Ratio of the second-harmonic to the first-harmonic amplitude of Stokes' second-order wave:
// (k H / 8) cosh kd (2 + cosh 2kd) / sinh^3 kd.
double stokes2_harmonic_ratio(double k, double depth, double height);

// First-order solitary wave (Boussinesq): eta = H sech^2(kappa (x - x0 - c t)), kappa and c as in
// SolitaryPaddle.
double solitary_elevation(double height, double depth, double x, double t, double x0 = 0.0,
                          double g = kStandardGravity);

// Second-order bound interaction of two linear components a_i cos theta_i and a_j cos theta_j,
// theta = omega t + phi - k x (omega^2 = g k tanh kd), in depth d. The second-order elevation
// they force is
//   eta2 = a_i a_j [G+ cos(theta_i + theta_j) + G- cos(theta_i - theta_j)]   (i != j)
// and, for one component with itself, a_i^2 G+(i, i) / 2 cos 2 theta_i (Stokes' second
// harmonic). G from the second-order potential problem (the kernels of Sharma & Dean 1981, in the
// form derived in docs/user-guide/waves.md#wavemakers-motion-type-wave): with
// W = omega_i +- omega_j, K = k_i +- k_j,
//   Q = g^2 k_i k_j / (omega_i omega_j),
//   R = -W (Q -+ omega_i omega_j) - [(g^2 k_i^2 - omega_i^4) / omega_i +- (g^2 k_j^2 -
//       omega_j^4) / omega_j] / 2,
//   B = R / (g K tanh(K d) - W^2)   (the bound potential's amplitude per a_i a_j),
//   G = [W B - (Q -+ omega_i omega_j - omega_i^2 - omega_j^2) / 2] / g.
// `sum` picks G+ (true) or G- (false). G- is symmetric in i, j and tends to Longuet-Higgins &
// Stewart's (1962) set-down, -g (2 c_g / c - 1/2) / (g d - c_g^2), as omega_j -> omega_i.
// Throws std::invalid_argument for G- of two equal frequencies (no bound long wave).
double second_order_kernel(double omega_i, double k_i, double omega_j, double k_j, double depth,
                           bool sum, double g = kStandardGravity);

// The volume flux of the pair's difference-frequency bound wave, bound potential plus the
// waves' Stokes flux, per a_i a_j: F = B- tanh(K d) + (g k_i / omega_i + g k_j / omega_j) / 2,
// the amplitude of q2 = F cos(theta_i - theta_j). Mass conservation of the bound wave,
// (omega_i - omega_j) G- = (k_i - k_j) F, holds exactly (a test checks it).
double subharmonic_flux(double omega_i, double k_i, double omega_j, double k_j, double depth,
                        double g = kStandardGravity);

// Subharmonic piston motion of the pair: X2 = P a_i a_j sin(psi_i - psi_j), psi = omega t + phi
// (the paddle's phase of each component), from the volume the paddle must displace: the
// water between the paddle and a section far away changes only by what crosses that section,
// so to second order X2 d = int q2 dt - slow part of X1 eta1(0) (- the near field's excess of
// slow second-order volume), q2 the bound wave's flux (subharmonic_flux). With the
// progressive first-order field, X1 = a/F sin psi and eta1(0) = a cos psi (F the piston's
// transfer function), this gives
//   P = G- / ((k_i - k_j) d) - (1/F_i - 1/F_j) / (2 d),
// the first term the bound wave's depth-averaged velocity (the long-wave, mass-flux form of
// subharmonic generation; Sand 1982), exact as the band narrows. Left out (Schaffer 1996 keeps
// them): the first-order evanescent modes' elevation at the paddle in X1 eta1(0) (in
// quadrature; of order (k_i - k_j) d relative to P) and the near field's second-order volume;
// both grow with the pair's separation (docs/user-guide/waves.md#wavemakers-motion-type-wave).
double subharmonic_piston(double omega_i, double k_i, double omega_j, double k_j, double depth,
                          double g = kStandardGravity);

// What a regular wave of height H, period T in depth d is, and which theory describes it.
struct WaveAssessment {
  double height = 0, period = 0, depth = 0;
  double k = 0, length = 0, kd = 0, celerity = 0, group_celerity = 0;
  double steepness = 0;         // H / L
  double ursell = 0;            // H L^2 / d^3
  double relative_depth = 0;    // d / L
  double d_gt2 = 0, h_gt2 = 0;  // Le Mehaute's (1976) chart coordinates d / (g T^2), H / (g T^2)
  double breaking_height = 0;   // Miche (1944): 0.142 L tanh(kd)
  double harmonic_ratio = 0;    // a2 / a1 of Stokes' second order
  std::string depth_regime;     // shallow (d/L < 1/20), intermediate, deep (d/L > 1/2)
  std::string theory;           // the lowest-order theory that describes the wave
  double stroke = 0;            // full paddle stroke S at the SWL, first order [m]
  double stroke2 = 0;           // second-order (Madsen) term amplitude [m], pistons
  double transfer = 0;          // H / S
  std::vector<std::string> warnings;
};

// The criteria (documented in docs/user-guide/waves.md#wavemakers-motion-type-wave, not a chart
// read by eye):
// - breaking: H >= the Miche limit;
// - cnoidal regime: Ursell number > 26 (the Stokes/cnoidal boundary of Le Mehaute's chart,
//   Hedges 1995 discusses it): Stokes theories and Stokes paddles are outside their validity;
// - Stokes second order is needed when a2/a1 >= 0.02 (the second harmonic is 2 % of the first
//   or more); it is itself invalid when a2/a1 >= 1/4 (a secondary crest appears in the trough);
// - otherwise linear theory.
// `order` (1 or 2) is the generation order the case asks for: warnings name a mismatch. `dp`
// (> 0) adds the resolution checks H/dp >= 10 and L/dp >= 50.
WaveAssessment assess_regular_wave(double height, double period, double depth,
                                   const PaddleGeometry& paddle, int order, double dp = 0.0,
                                   double g = kStandardGravity);

}  // namespace swell::waves
