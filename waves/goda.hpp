// Goda's wave-pressure formula for vertical walls and caisson breakwaters: Goda (1974), with the
// obliquity of Tanimoto et al. (1976) and the modification factors lambda1..3 of Takahashi et al.
// (1994), as given in Goda (2000) "Random Seas and Design of Maritime Structures", sec. 4.2, and
// the Coastal Engineering Manual (USACE 2006), part VI, chapter 5. Pure maths, SI units.
//
//   eta*  = 0.75 (1 + cos b) lambda1 H                     height of the pressure's top above SWL
//   p1    = 0.5 (1 + cos b) (lambda1 a1 + lambda2 a2 cos^2 b) rho g H   at the SWL
//   p2    = p1 / cosh(k h)                                 at the sea bed (depth h)
//   p3    = a3 p1                                          at the caisson base (depth h')
//   p4    = a4 p1,  a4 = 1 - hc*/eta*,  hc* = min(eta*, hc)   at the crest (if eta* > hc)
//   pu    = 0.5 (1 + cos b) a1 a3 lambda3 rho g H          uplift at the seaward toe
//   a1    = 0.6 + 0.5 [2kh / sinh(2kh)]^2
//   a2    = min{ (hb - d) / (3 hb) (H/d)^2, 2d/H }
//   a3    = 1 - (h'/h) [1 - 1/cosh(kh)]
// with k from linear dispersion at depth h (waves/dispersion.hpp). The face pressure is linear
// from p3 at the base to p1 at the SWL (the line through p2 at the bed) and from p1 to zero at
// eta* above it, cut at the crest; the uplift is triangular from pu at the toe to 0 at the heel.
//
// Goda's p is the wave pressure: below the SWL it is the pressure in excess of the still-water
// hydrostatic pressure rho g (-z); above the SWL it is the whole pressure. It is an envelope of
// the largest pressures under the design wave (not a simultaneous distribution), for
// non-breaking and breaking waves alike, but not for the impulsive pressures of waves breaking
// on a high mound: Takahashi's impulsive coefficient alpha_I (a2 -> max(a2, alpha_I)) is not
// implemented here (its coefficients were not available to check against a source). The design
// practice of turning the wave direction up to 15 degrees towards the wall normal (Goda 2000) is
// left to the caller: `beta` is used as given.
#pragma once

#include <limits>

#include "waves/dispersion.hpp"

namespace swell::waves {

struct GodaInput {
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();
  double height = 0.0;             // H [m]: H_max for design, the wave height of a regular wave
  double period = 0.0;             // T [s]
  double depth = 0.0;              // h [m]: water depth in front of the structure (mound toe)
  double base_depth = kUnset;      // h' [m]: depth of the caisson base below the SWL (default h)
  double berm_depth = kUnset;      // d [m]: depth above the armour / berm crown (default h')
  double breaking_depth = kUnset;  // h_b [m]: depth 5 H_1/3 seaward of the wall (default h)
  double freeboard = std::numeric_limits<double>::infinity();  // h_c [m]: crest above SWL
  double beta_deg = 0.0;  // angle between the wave direction and the wall normal [deg]
  double lambda1 = 1.0, lambda2 = 1.0, lambda3 = 1.0;  // modification factors
  double width = 0.0;   // B [m]: caisson width, for the uplift force (0: not computed)
  double rho = 1000.0;  // [kg/m^3]
  double g = kStandardGravity;
};

struct GodaPressure {
  GodaInput input;  // with the defaults resolved (h', d, h_b set)
  double length = 0.0, kh = 0.0;
  double eta_star = 0.0, hc_star = 0.0;  // [m] above the SWL
  double alpha1 = 0.0, alpha2 = 0.0, alpha3 = 0.0, alpha4 = 0.0;
  double p1 = 0.0, p2 = 0.0, p3 = 0.0, p4 = 0.0, pu = 0.0;  // [Pa]
  double force = 0.0;          // horizontal force per metre of wall [N/m]
  double moment = 0.0;         // its moment about the caisson base [N m/m]
  double uplift_force = 0.0;   // 0.5 pu B [N/m]
  double uplift_moment = 0.0;  // about the heel, (2/3) B times the uplift force [N m/m]

  // Wave pressure on the face at height z above the SWL [Pa]: the piecewise-linear
  // distribution above for -h' <= z <= hc*, 0 outside (below the base, above the crest or
  // above eta*).
  double pressure(double z) const;
};

// Evaluates the formula. Throws std::invalid_argument naming the parameter unless H, T, h > 0,
// 0 < h' <= h, 0 < d <= h', h_b >= d, h_c >= 0, |beta| < 90, lambda >= 0, B >= 0, rho, g > 0.
GodaPressure goda_pressure(const GodaInput& in);

}  // namespace swell::waves
