// What each libFuzzer harness does with one input, as plain functions: the harnesses
// (fuzz_*.cpp, clang + sanitizers, scripts/fuzz) call them, and tests/test_fuzz_corpus.cpp
// replays the seed corpora through them in the normal build under ctest. Each returns
// normally for every input: an exception that escapes (anything but the documented error
// types) is a finding.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

#include "case/reader.hpp"
#include "case/setup.hpp"
#include "geometry/mesh_solid.hpp"

namespace swell::fuzz {

// The case-file parser on arbitrary bytes: a CaseSpec or a CaseError (or invalid_argument).
inline void case_parse(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const CaseSpec spec = parse_case_text(text, "fuzz.yaml");
    (void)spec;
  } catch (const CaseError&) {
  } catch (const std::invalid_argument&) {
  }
}

// The mesh reader and checks on arbitrary STL bytes (written to `scratch`), `repair` chosen by
// the first byte: it loads or throws MeshError; CGAL's own precondition failures escape and
// are findings.
inline void mesh_stl(const std::uint8_t* data, std::size_t size, const std::string& scratch) {
  if (size < 1) return;
  const bool repair = data[0] & 1;
  {
    std::ofstream out(scratch, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    geometry::MeshReport report;
    const auto mesh = geometry::MeshSolid::load(scratch, {}, repair, &report);
    (void)mesh->contains(Eigen::Vector3d(0.1, 0.2, 0.3));
  } catch (const geometry::MeshError&) {
  }
}

// Parse + fill on arbitrary case text (shapes, CSG, fills, the size estimate, the set-up checks,
// the hydrostatic start), one thread, at most 20,000 particles so each input stays fast: what
// the fill cannot do must end in CaseError (exit 2 in `swell`).
inline void parse_fill(const std::uint8_t* data, std::size_t size) {
  omp_set_num_threads(1);
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    CaseSpec spec = parse_case_text(text, "fuzz.yaml");
    spec.max_particles = std::min(spec.max_particles, 2.0e4);
    if (spec.dim == 2)
      (void)setup_case<2>(spec);
    else
      (void)setup_case<3>(spec);
  } catch (const CaseError&) {
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace swell::fuzz
