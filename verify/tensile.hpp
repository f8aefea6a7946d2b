// `tensile`: a periodic particle lattice under uniform tension (negative pressure) and
// compression, seeded with a small random displacement: how fast the lattice loses its order
// (the tensile instability, Swegle et al. 1995; the pairing instability of kernels with a
// negative-slope region, Dehnen & Aly 2012), with the Wendland and cubic-spline kernels and with
// Fickian shifting as the correction. An unperturbed lattice must stay a lattice (equilibrium).
#pragma once

#include "verify/verify.hpp"

namespace swell::verify {

Result run_tensile(const Options& opt);

}  // namespace swell::verify
