#include "geometry/shape_factory.hpp"

#include <filesystem>
#include <sstream>

#include "geometry/primitives.hpp"

namespace swell::geometry {
namespace {

std::string with_line(int line, const std::string& message) {
  return line > 0 ? "line " + std::to_string(line) + ": " + message : message;
}

ShapePtr build_mesh(const ShapeSpec& spec, int dim, const std::string& base_dir,
                    std::vector<MeshReport>* reports) {
  if (spec.file.empty()) throw ShapeError(spec.line, "mesh: no file given");
  std::filesystem::path path(spec.file);
  if (path.is_relative() && !base_dir.empty()) path = std::filesystem::path(base_dir) / path;
  if (dim == 2 && !spec.slice_y)
    throw ShapeError(spec.line, "mesh " + spec.file +
                                    " in a 2D case needs slice_y (the plane y = slice_y cuts "
                                    "it; the section's x, z become the case's x, y)");
  if (dim == 3 && spec.slice_y)
    throw ShapeError(spec.line, "mesh " + spec.file + ": slice_y only applies to 2D cases");

  MeshReport report;
  std::shared_ptr<MeshSolid> mesh;
  try {
    mesh = MeshSolid::load(path.string(), spec.placement, spec.repair, &report);
  } catch (const MeshError& e) {
    throw ShapeError(spec.line, e.what());
  }
  if (reports) reports->push_back(report);
  if (dim == 3) return mesh;

  const double y0 = *spec.slice_y;
  auto loops = mesh->slice_y(y0);
  if (loops.empty()) {
    const Aabb b = mesh->bounds();
    std::ostringstream s;
    s << "mesh " << spec.file << ": the plane y = " << y0
      << " misses it (placed mesh spans y = " << b.min.y() << " to " << b.max.y() << ")";
    throw ShapeError(spec.line, s.str());
  }
  std::ostringstream name;
  name << "section y = " << y0 << " of mesh " << spec.file;
  try {
    return std::make_shared<PolygonShape>(std::move(loops), name.str());
  } catch (const std::invalid_argument& e) {
    throw ShapeError(spec.line, e.what());
  }
}

}  // namespace

ShapeError::ShapeError(int line, const std::string& message)
    : std::invalid_argument(with_line(line, message)), line_(line), message_(message) {}

ShapePtr build_shape(const ShapeSpec& spec, int dim, const std::string& base_dir,
                     std::vector<MeshReport>* reports) {
  if (dim != 2 && dim != 3) throw ShapeError(spec.line, "dim must be 2 or 3");
  using T = ShapeSpec::Type;
  try {
    switch (spec.type) {
      case T::Box:
        return std::make_shared<BoxShape>(spec.box.min, spec.box.max, dim);
      case T::Cylinder:
        return std::make_shared<CylinderShape>(spec.p1, spec.p2, spec.radius, dim);
      case T::Sphere:
        return std::make_shared<SphereShape>(spec.p1, spec.radius, dim);
      case T::Polygon: {
        if (dim != 2) throw ShapeError(spec.line, "polygon: only in 2D cases (use a mesh in 3D)");
        std::vector<Eigen::Vector2d> loop;
        for (const auto& p : spec.points) loop.push_back(p.head<2>());
        std::vector<std::vector<Eigen::Vector2d>> loops{std::move(loop)};
        return std::make_shared<PolygonShape>(std::move(loops));
      }
      case T::Mesh:
        return build_mesh(spec, dim, base_dir, reports);
      case T::Union: {
        std::vector<ShapePtr> children;
        for (const auto& c : spec.children)
          children.push_back(build_shape(c, dim, base_dir, reports));
        return std::make_shared<UnionShape>(std::move(children));
      }
      case T::Difference: {
        if (spec.children.size() < 2)
          throw ShapeError(spec.line, "difference: needs a shape and at least one to remove");
        ShapePtr base = build_shape(spec.children[0], dim, base_dir, reports);
        std::vector<ShapePtr> cut;
        for (std::size_t i = 1; i < spec.children.size(); ++i)
          cut.push_back(build_shape(spec.children[i], dim, base_dir, reports));
        return std::make_shared<DifferenceShape>(std::move(base), std::move(cut));
      }
    }
  } catch (const ShapeError&) {
    throw;
  } catch (const std::invalid_argument& e) {  // parameter checks of the primitives
    throw ShapeError(spec.line, e.what());
  }
  throw ShapeError(spec.line, "unknown shape type");
}

}  // namespace swell::geometry
