// libFuzzer harness: the mesh reader and checks (geometry/mesh_solid) on arbitrary STL bytes,
// with `repair` chosen by the first byte. Every input must load or throw MeshError; CGAL's own
// precondition failures (std::exception) are findings too, reported as such. Run by
// scripts/fuzz.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "geometry/mesh_solid.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const bool repair = data[0] & 1;
  static const std::string path = "/tmp/swell_fuzz_mesh_" + std::to_string(::getpid()) + ".stl";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    swell::geometry::MeshReport report;
    const auto mesh = swell::geometry::MeshSolid::load(path, {}, repair, &report);
    (void)mesh->contains(Eigen::Vector3d(0.1, 0.2, 0.3));
  } catch (const swell::geometry::MeshError&) {
  }
  return 0;
}
