// Viscous flows with analytic solutions, run by the WCSPH solver itself:
//   `taylor_green`  the 2D Taylor-Green vortex in a doubly periodic box: the kinetic energy's
//                   decay rate against exp(-16 pi^2 nu t / L^2), at two resolutions;
//   `poiseuille`    plane Poiseuille flow started from rest in a channel periodic along x
//                   (DBC walls): the velocity profile against the transient series solution
//                   (Morris, Fox & Zhu 1997, eq. 21) at several times;
//   `time_order`    temporal convergence of the symplectic and Verlet integrators at fixed
//                   dt on the Taylor-Green vortex: the fitted order of the final state's error.
#pragma once

#include "verify/verify.hpp"

namespace swell::verify {

Result run_taylor_green(const Options& opt);
Result run_poiseuille(const Options& opt);
Result run_time_order(const Options& opt);

}  // namespace swell::verify
