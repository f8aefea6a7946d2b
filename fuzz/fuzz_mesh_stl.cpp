// libFuzzer harness: the mesh reader and checks (geometry/mesh_solid) on arbitrary STL bytes,
// with `repair` chosen by the first byte. Every input must load or throw MeshError; CGAL's own
// precondition failures (std::exception) are findings too, reported as such. Run by
// scripts/fuzz.
#include <unistd.h>

#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/swell_fuzz_mesh_" + std::to_string(::getpid()) + ".stl";
  swell::fuzz::mesh_stl(data, size, path);
  return 0;
}
