#include "case/geometry.hpp"

#include <filesystem>
#include <string>

#include "case/reader.hpp"
#include "geometry/shape_factory.hpp"

namespace swell {

std::vector<geometry::BodyGeometry> case_geometry(const CaseSpec& spec,
                                                  std::vector<geometry::MeshReport>* meshes) {
  const std::string base_dir = std::filesystem::path(spec.file).parent_path().string();
  std::vector<geometry::BodyGeometry> out;
  out.reserve(spec.bodies.size());
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    const BodySpec& b = spec.bodies[i];
    geometry::BodyGeometry g;
    g.name = b.name;
    g.fluid = b.kind == BodySpec::Kind::Fluid;
    g.walls_inside = b.walls == BodySpec::Walls::Inside;
    g.layers = b.layers;
    g.open = b.open;
    if (g.fluid && b.fill_below) {
      g.fill_below = b.fill_below;
      g.container = b.fill_container;
    } else {
      try {
        g.shape = geometry::build_shape(b.shape, spec.dim, base_dir, meshes);
      } catch (const geometry::ShapeError& e) {
        throw CaseError(spec.file, e.line() > 0 ? e.line() : b.line,
                        "bodies[" + std::to_string(i) + "].shape: " + e.message());
      }
    }
    out.push_back(std::move(g));
  }
  return out;
}

}  // namespace swell
