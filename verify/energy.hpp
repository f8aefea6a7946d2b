// `swell verify energy`: total energy conservation of the compressible path (Sod tube) at a
// sequence of fixed time steps; the drift must fall at the integrator's order (2).
#pragma once

#include "verify/verify.hpp"

namespace swell::verify {

Result run_energy(const Options& opt);

}  // namespace swell::verify
