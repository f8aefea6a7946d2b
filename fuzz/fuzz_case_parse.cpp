// libFuzzer harness: the case-file parser (io/case_file) on arbitrary bytes. Every input must
// end in a CaseSpec or a CaseError; a crash, a sanitizer report, a hang or unbounded memory is
// a finding. Built with -DSWELL_FUZZ=ON (clang), run by scripts/fuzz.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "io/case_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const swell::CaseSpec spec = swell::parse_case_text(text, "fuzz.yaml");
    (void)spec;
  } catch (const swell::CaseError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
