// Linear (Airy) wave dispersion: omega^2 = g k tanh(k d), and the quantities derived from it.
// Pure maths, SI units, no allocation; shared by bc/ (wavemakers), validation/ (wave analysis,
// the OpenFOAM wave cases) and the `swell waves` command.
#pragma once

namespace swell::waves {

inline constexpr double kStandardGravity = 9.81;  // [m/s^2], the case files' usual g

// Wave number k [rad/m] of a linear wave of angular frequency omega [rad/s] in depth d [m]:
// the positive root of omega^2 = g k tanh(k d), by Newton's method from the explicit
// approximation of Fenton & McKee (1990), to a relative change below 1e-15 (at most 50
// iterations; the function is convex in k, so Newton from above converges monotonically).
// Throws std::invalid_argument unless omega > 0, d > 0 and g > 0.
double wave_number(double omega, double depth, double g = kStandardGravity);

// Wave length L = 2 pi / k [m] of a wave of period T [s] in depth d [m].
double wave_length(double period, double depth, double g = kStandardGravity);

// Phase speed omega / k and group speed c_g = n c, n = (1 + 2kd / sinh 2kd) / 2 [m/s].
double phase_speed(double omega, double depth, double g = kStandardGravity);
double group_speed(double omega, double depth, double g = kStandardGravity);

// The ratio n = c_g / c (1/2 in deep water, 1 in shallow water), for k d given.
double group_ratio(double kd);

}  // namespace swell::waves
