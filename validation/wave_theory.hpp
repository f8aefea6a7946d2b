// The wave a case's paddle is meant to make, as a reference series for `swell validate`
// (references: {name: ..., theory: paddle}): at a height gauge, the still-water level plus the
// paddle signal's target elevation (waves/wavemaker.hpp: linear components and, for
// second-order generation, Stokes' bound second harmonic; Goring's soliton for a solitary
// wave), switched on by the motion's ramp at the time a front travelling at the group velocity
// of the peak component would reach the gauge. No near field, no reflections: compare in a
// window after the front and before any echo.
#pragma once

#include <string>

#include "case/spec.hpp"
#include "validation/metrics.hpp"

namespace swell {

// The target level [m] at `gauge` (a height gauge of `spec`) every `dt` from 0 to `t_end`.
// The case must have exactly one `type: wave` piston or flap whose box (or shape) bounds give
// its rest face (the largest x). Throws std::invalid_argument naming what is missing.
Series paddle_theory_series(const CaseSpec& spec, const std::string& gauge, double dt,
                            double t_end);

}  // namespace swell
