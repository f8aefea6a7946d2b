// libFuzzer harness: parse + fill (io/case_file, io/case_setup, geometry/) on arbitrary case
// text: shapes, CSG, fills, the size estimate, the setup checks and the hydrostatic start.
// limits.max_particles is capped at 20000 so that each input stays fast; what the fill cannot
// do must end in CaseError (exit 2 in `swell`). Run by scripts/fuzz.
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "io/case_file.hpp"
#include "io/case_setup.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  omp_set_num_threads(1);
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    swell::CaseSpec spec = swell::parse_case_text(text, "fuzz.yaml");
    spec.max_particles = std::min(spec.max_particles, 2.0e4);
    if (spec.dim == 2)
      (void)swell::setup_case<2>(spec);
    else
      (void)swell::setup_case<3>(spec);
  } catch (const swell::CaseError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
