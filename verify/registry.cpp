// The list of verifications `swell verify` knows, in report order. A verification is added
// here with one line: {name, title, function} (declared in its own verify/*.hpp).
#include "verify/verify.hpp"

namespace swell::verify {

const std::vector<Verification>& all() {
  static const std::vector<Verification> list = {};
  return list;
}

}  // namespace swell::verify
