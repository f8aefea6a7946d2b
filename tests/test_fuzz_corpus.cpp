// The fuzz harnesses' seed corpora (fuzz/corpus/) replayed through the same entry points
// (fuzz/fuzz_targets.hpp) in the normal build: every seed must end in a result or one of the
// documented errors, never an escaping exception. CI runs this instead of fuzzing (the
// libFuzzer runs, with sanitizers, are `scripts/fuzz`).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz/fuzz_targets.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<std::uint8_t> bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> seeds(const char* corpus) {
  std::vector<fs::path> v;
  for (const auto& e : fs::directory_iterator(fs::path(SWELL_SOURCE_DIR) / "fuzz/corpus" / corpus))
    if (e.is_regular_file()) v.push_back(e.path());
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

TEST(FuzzCorpus, CaseSeedsParseOrFailCleanly) {
  const auto files = seeds("case");
  ASSERT_GE(files.size(), 20u);
  for (const auto& f : files) {
    const auto b = bytes(f);
    EXPECT_NO_THROW(swell::fuzz::case_parse(b.data(), b.size())) << f;
  }
}

TEST(FuzzCorpus, CaseSeedsFillOrFailCleanly) {
  const int threads = omp_get_max_threads();
  for (const auto& f : seeds("case")) {
    const auto b = bytes(f);
    EXPECT_NO_THROW(swell::fuzz::parse_fill(b.data(), b.size())) << f;
  }
  omp_set_num_threads(threads);
}

TEST(FuzzCorpus, StlSeedsLoadOrFailCleanly) {
  const auto files = seeds("stl");
  ASSERT_GE(files.size(), 5u);
  const fs::path dir = fs::path(SWELL_BINARY_DIR) / "test_out" / "fuzz_corpus";
  fs::create_directories(dir);
  for (const auto& f : files) {
    const auto b = bytes(f);
    EXPECT_NO_THROW(swell::fuzz::mesh_stl(b.data(), b.size(), (dir / "seed.stl").string())) << f;
  }
}
