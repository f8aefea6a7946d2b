// Tolerances for values read back from the particle state, whose velocity and density are
// stored in float unless built with SWELL_DOUBLE_STATE (solver/state/types.hpp): a stored value
// is the computed one rounded once, within kStateEps / 2 of it (relative).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "solver/state/types.hpp"

namespace swell {

// Tolerance for a stored value expected to be `expected` after arithmetic good to `abs`.
inline double stored_tol(double expected, double abs = 1e-15) {
  return abs + kStateEps * std::abs(expected);
}

}  // namespace swell

namespace swell {

// What storing the velocities may add to a momentum drift over `steps` steps: the velocity a
// step ends with is rounded once when stored (symplectic: the corrector's v^n + dt a, from the
// stored v^n; the predictor's rounded half-step velocity is not carried over; Verlet alike), by
// at most kStateEps / 2 of it; `scale` is sum m |v|. With a double state this is far below the
// 1e-12 * scale that the exactly antisymmetric pair terms leave.
inline double momentum_rounding(double scale, int steps) {
  return steps * 0.5 * kStateEps * scale;
}

}  // namespace swell
