// Wavemaker kinematics: the paddle motion that makes a given wave (pure maths, SI units).
//
// Conventions. A paddle moves along its `direction` (x here), the waves it makes travel the same
// way, and X(t) is its displacement at the still-water level (SWL) from its rest position; a
// flap turns about a hinge `hinge_height` above the bed (negative: below the bed, as in a flume
// with a paddle pit), and X is the horizontal displacement of its SWL point. A linear wave
// component of surface amplitude a and angular frequency w is made, far from the paddle (past
// the evanescent modes, ~2-3 depths), by the paddle motion
//     eta(0, t) = a cos(w t + phi)   <=>   X(t) = (a / F(kd)) sin(w t + phi),
// i.e. the surface elevation is in phase with the paddle velocity, and F = H / S is the Biesel
// (1951) transfer function of the paddle (wave height over full stroke at the SWL).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "waves/dispersion.hpp"

namespace swell::waves {

struct PaddleGeometry {
  enum class Type { Piston, Flap };
  Type type = Type::Piston;
  double depth = 0.0;         // still-water depth at the paddle [m]
  double hinge_height = 0.0;  // flap: hinge height above the bed [m] (< depth; may be < 0)
};

// Biesel transfer function F = H / S for a paddle whose displacement profile over the depth is
// f(z) (1 at the SWL): F = 4 k sinh(kd) I / (sinh 2kd + 2kd), I = int_{-d}^{0} f(z) cosh k(d+z)
// dz (Dean & Dalrymple 1991, sec. 6.2). Piston (f = 1): F = 2 (cosh 2kd - 1) / (sinh 2kd + 2kd).
// Flap hinged at height l above the bed (f linear from 0 at the hinge to 1 at the SWL, 0 below
// the hinge; for l < 0 the flap reaches the bed with f(bed) = -l / (d - l)): closed form below.
// k [rad/m] is the component's wave number. Throws std::invalid_argument for a hinge at or above
// the SWL or a non-positive depth or k.
double transfer_function(const PaddleGeometry& paddle, double k);

// One term of a paddle displacement: X(t) = amplitude sin(omega t + phase).
struct PaddleComponent {
  double amplitude = 0.0;  // [m] at the SWL
  double omega = 0.0;      // [rad/s]
  double phase = 0.0;      // [rad]
};

// A solitary wave by Goring's (1978) piston trajectory: the paddle moves with the depth-averaged
// velocity of the wave under it, dX/dt = c eta(X, t) / (d + eta(X, t)), eta = H sech^2(kappa (c
// (t - t0) - X)), kappa = sqrt(3 H / (4 d^3)), c = sqrt(g (d + H)); integrated in closed form,
// X + S/2 = (H / (kappa d)) tanh(kappa (c (t - t0) - X)) + S/2, solved per t by Newton's method
// (monotone, unique root). Stroke S = 2 H / (kappa d); duration 2 (3.8 + H/d) / (kappa c)
// (Goring's choice, where the motion is within 0.1 % of its end points); t0 is the middle.
struct SolitaryPaddle {
  double height = 0.0, depth = 0.0, g = kStandardGravity;
  double kappa = 0.0, celerity = 0.0, stroke = 0.0, duration = 0.0;
  double start = 0.0;  // the trajectory's X at t = 0 (~ -S/2), subtracted so X(0) = 0
};
SolitaryPaddle make_solitary_paddle(double height, double depth, double g = kStandardGravity);

// A paddle signal: a sum of components, or a solitary-wave trajectory. Value type; evaluation
// allocates nothing. displacement(t) and velocity(t) are the exact function and derivative. Before
// t = 0 the components are evaluated as they are (ramping is the motion law's business); the
// solitary trajectory is held at its ends outside [0, duration].
struct PaddleSignal {
  PaddleGeometry paddle;
  std::vector<PaddleComponent> components;
  bool solitary = false;
  SolitaryPaddle soliton;

  // The wave the signal is meant to make, for active absorption (bc/absorption.hpp) and checks:
  // free linear components eta = a cos(w t + phi - k x) and, for a second-order regular wave,
  // Stokes' bound second harmonic a2 cos(2 (w t + phi - k x)); a solitary signal uses its
  // soliton. Filled by regular_paddle, solitary_paddle and linear_paddle.
  struct TargetComponent {
    double amplitude = 0.0, omega = 0.0, phase = 0.0, k = 0.0;
  };
  std::vector<TargetComponent> target;
  double bound_second_harmonic = 0.0;  // a2 [m] (regular order 2), else 0

  // Second-order difference-frequency terms of a set of linear components (second_order_paddle):
  // over the first `pair_components` components / target components, for every pair i < j at
  // the packed index p = i n - i (i + 1) / 2 + j - i - 1, the paddle term
  // pair_paddle[p] sin(psi_i - psi_j), psi = w t + phi, and the bound long wave
  // pair_surface[p] cos(theta_i - theta_j), theta = psi - k x. Empty for first order.
  std::size_t pair_components = 0;
  std::vector<double> pair_paddle, pair_surface;

  double displacement(double t) const;
  double velocity(double t) const;
  // Target surface elevation at distance x [m] from the paddle's rest position, time t
  // (unramped; no evanescent near field). No allocation.
  double elevation(double t, double x) const;
  // The angular frequency of the largest target component (0 for a solitary wave).
  double peak_omega() const;
  // The shortest period among the components (the solitary duration), for sampling.
  double shortest_period() const;
  // Largest |X| over the signal, bounded by the sum of amplitudes (or the solitary stroke).
  double amplitude_bound() const;
};

// A regular wave of height H and period T in depth d, first or second order. Second order
// (pistons only) adds Madsen's (1971) correction, the paddle term at 2 omega that cancels the
// spurious free second harmonic a first-order paddle makes:
//   X(t) = S/2 sin(w t + phi) + (H^2 / (32 d)) (3 cosh kd / sinh^3 kd - 2 / F) sin(2 w t + 2 phi)
// with S = H / F and F the piston transfer function. Throws std::invalid_argument for order 2
// with a flap (not implemented: Sulisz & Hudspeth 1993 would be the reference), for an order not
// 1 or 2, or non-positive H, T.
PaddleSignal regular_paddle(const PaddleGeometry& paddle, double height, double period, int order,
                            double phase = 0.0, double g = kStandardGravity);

// A solitary wave of height H (Goring 1978), for a piston.
PaddleSignal solitary_paddle(const PaddleGeometry& paddle, double height,
                             double g = kStandardGravity);

// Linear paddle signal for a set of surface components eta(0, t) = sum a_i cos(w_i t + phi_i).
struct SurfaceComponent {
  double amplitude = 0.0;  // a [m]
  double omega = 0.0;      // [rad/s]
  double phase = 0.0;      // phi [rad]
};
PaddleSignal linear_paddle(const PaddleGeometry& paddle,
                           const std::vector<SurfaceComponent>& surface,
                           double g = kStandardGravity);

// The same components generated to second order (pistons only): the linear paddle signal plus,
// for every pair of components, the subharmonic piston motion that makes their bound long wave
// (subharmonic_piston, waves/theory.hpp), so that the sea leaves the paddle with its
// second-order set-down and without the free long waves a first-order paddle sheds; the target
// elevation carries the bound long wave (second_order_kernel). Sum-frequency terms are not
// generated. n components give n (n - 1) / 2 pair terms, evaluated without allocation in
// O(n^2) multiplications and about n + n^2 / 256 sines per call. Throws
// std::invalid_argument for a flap or two components of the same frequency.
PaddleSignal second_order_paddle(const PaddleGeometry& paddle,
                                 const std::vector<SurfaceComponent>& surface,
                                 double g = kStandardGravity);

// Surface elevation of linear components at a distance x from the paddle:
// eta(x, t) = sum a_i cos(w_i t + phi_i - k_i x).
double linear_elevation(const std::vector<SurfaceComponent>& surface, double depth, double x,
                        double t, double g = kStandardGravity);

}  // namespace swell::waves
