// libFuzzer harness: the case-file parser (case/reader) on arbitrary bytes. Every input must
// end in a CaseSpec or a CaseError; a crash, a sanitizer report, a hang or unbounded memory is
// a finding. Built with -DSWELL_FUZZ=ON (clang), run by scripts/fuzz.
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  swell::fuzz::case_parse(data, size);
  return 0;
}
