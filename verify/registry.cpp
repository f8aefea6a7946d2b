// The list of verifications `swell verify` knows, in report order. A verification is added
// here with one line: {name, title, function} (declared in its own verify/*.hpp).
#include "verify/angular_momentum.hpp"
#include "verify/energy.hpp"
#include "verify/flows.hpp"
#include "verify/noh.hpp"
#include "verify/operators.hpp"
#include "verify/sod.hpp"
#include "verify/tensile.hpp"
#include "verify/verify.hpp"

namespace swell::verify {

const std::vector<Verification>& all() {
  static const std::vector<Verification> list = {
      {"consistency", "linear fields: corrected operators exact, uncorrected not", run_consistency},
      {"gradient_convergence", "SPH gradient: smoothing and discretisation errors",
       run_gradient_convergence},
      {"laplacian", "Morris Laplacian: smoothing and discretisation errors", run_laplacian},
      {"kernels", "second-order interpolation of every kernel", run_kernels},
      {"angular_momentum", "a rotating free disc: linear and angular momentum",
       run_angular_momentum},
      {"taylor_green", "Taylor-Green vortex (periodic box): viscous decay rate", run_taylor_green},
      {"poiseuille", "Poiseuille flow from rest: profile against the series solution",
       run_poiseuille},
      {"time_order", "temporal order of the symplectic and Verlet integrators (fixed dt)",
       run_time_order},
      {"tensile",
       "a periodic lattice under tension and compression: tensile and pairing instability",
       run_tensile},
      {"sod", "Sod shock tube: compressible SPH against the exact Riemann solution", run_sod},
      {"energy", "Total energy conservation of the compressible path against dt", run_energy},
      {"noh", "planar Noh problem: a cold stream into a wall (jump conditions, wall heating)",
       run_noh},
  };
  return list;
}

}  // namespace swell::verify
