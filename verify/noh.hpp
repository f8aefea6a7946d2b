// `swell verify noh`: the planar Noh (1987) problem with the compressible path: cold gas
// streaming at v = -1 into a mirror wall at x = 0. Exact solution (gamma = 5/3): a shock
// leaving the wall at speed 1/3, behind it rho = 4, v = 0, u = 1/2, p = 4/3; ahead of it the
// undisturbed stream (rho = 1, v = -1, u = 0). The known SPH defect is "wall heating": the
// particles that hit the wall first are over-heated by the artificial viscosity and keep a
// density below 4 (Noh 1987, J. Comput. Phys. 72:78); it does not converge away in L-infinity.
#pragma once

#include <memory>

#include "solver/compressible/gas_solver.hpp"
#include "verify/verify.hpp"

namespace swell::verify {

// n equal-mass particles on [0, 1] (spacing 1/n), v = -1, u = u0, gamma = 5/3, cubic spline at
// eta = 1.2, mirror wall at x = 0 (the far wall at x = 3 is out of reach for the whole run).
std::unique_ptr<compressible::GasSolver<1>> make_noh_1d(int n, double u0 = 1e-6);

Result run_noh(const Options& opt);

}  // namespace swell::verify
