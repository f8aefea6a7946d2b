// libFuzzer harness: parse + fill (case/reader, case/setup, geometry/) on arbitrary case
// text: shapes, CSG, fills, the size estimate, the setup checks and the hydrostatic start.
// limits.max_particles is capped at 20000 so that each input stays fast; what the fill cannot
// do must end in CaseError (exit 2 in `swell`). Run by scripts/fuzz.
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  swell::fuzz::parse_fill(data, size);
  return 0;
}
