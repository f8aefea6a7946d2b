// `angular_momentum`: a free disc of fluid in solid-body rotation (no gravity, no walls), run
// by the WCSPH solver: total linear and angular momentum over the run with artificial viscosity
// (pairwise forces along r_ab: both conserved to round-off), with laminar viscosity (the Lo &
// Shao / Morris force is along v_ab, not r_ab: angular momentum drifts, measured) and with the
// kernel-gradient correction (L_a != L_b: linear momentum no longer exact, measured).
#pragma once

#include "verify/verify.hpp"

namespace swell::verify {

Result run_angular_momentum(const Options& opt);

}  // namespace swell::verify
