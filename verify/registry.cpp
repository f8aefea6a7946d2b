// The list of verifications `swell verify` knows, in report order. A verification is added
// here with one line: {name, title, function} (declared in its own verify/*.hpp).
#include "verify/energy.hpp"
#include "verify/sod.hpp"
#include "verify/verify.hpp"

namespace swell::verify {

const std::vector<Verification>& all() {
  static const std::vector<Verification> list = {
      {"sod", "Sod shock tube: compressible SPH against the exact Riemann solution", run_sod},
      {"energy", "Total energy conservation of the compressible path against dt", run_energy},
  };
  return list;
}

}  // namespace swell::verify
