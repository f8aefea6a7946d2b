// Verifications of the interpolation and gradient operators (solver/physics/corrections.hpp):
//   consistency          linear fields on lattices, disordered sets and at a free surface: the
//                        corrected operators exact to round-off, the uncorrected ones not
//   gradient_convergence the SPH gradient of sin(2 pi x / lambda): smoothing error versus h at
//                        fixed dp/h, discretisation error versus dp/h at fixed h (Quinlan et al.
//                        2006), against the kernel's exact continuous smoothing error
//   laplacian            the same for the Laplacian of the laminar viscous term (Morris 1997)
//   kernels              second-order accuracy of every kernel's interpolation
#pragma once

#include "verify/verify.hpp"

namespace swell::verify {

Result run_consistency(const Options& opt);
Result run_gradient_convergence(const Options& opt);
Result run_laplacian(const Options& opt);
Result run_kernels(const Options& opt);

}  // namespace swell::verify
