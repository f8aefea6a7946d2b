// From a case file's ShapeSpec to a Shape: primitives and CSG (geometry/primitives.hpp) and
// triangle meshes (geometry/mesh_solid.hpp; in 2D cut by the plane y = slice_y).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/mesh_solid.hpp"
#include "geometry/shape.hpp"
#include "geometry/shape_spec.hpp"

namespace swell::geometry {

// A shape that cannot be built. what() is "line N: <message>" when the spec has a line
// (ShapeSpec::line), else the message alone; line() and message() give the parts, so the
// caller can name the case file as well.
class ShapeError : public std::invalid_argument {
 public:
  ShapeError(int line, const std::string& message);
  int line() const noexcept { return line_; }
  const std::string& message() const noexcept { return message_; }

 private:
  int line_;
  std::string message_;
};

// Builds the shape for a `dim`-dimensional case. Mesh paths are relative to `base_dir` (the
// case file's folder) unless absolute. Each mesh loaded appends its MeshReport to `reports`
// (if given), in the order the meshes appear in the spec. Throws ShapeError (a
// std::invalid_argument) for invalid parameters, unusable meshes (MeshError's message is
// kept), a 2D mesh without slice_y, or a slice that misses the mesh.
ShapePtr build_shape(const ShapeSpec& spec, int dim, const std::string& base_dir,
                     std::vector<MeshReport>* reports = nullptr);

}  // namespace swell::geometry
