// A shape as described in a case file: plain data, parsed by case/reader and turned into a
// geometry::Shape by geometry/shape_factory (build_shape).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "geometry/shapes.hpp"

namespace swell {

// Scale, then rotate (degrees about x, then y, then z), then translate. Applies to meshes.
struct Placement {
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d rotate_deg = Eigen::Vector3d::Zero();
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();
};

struct ShapeSpec {
  enum class Type { Box, Cylinder, Sphere, Polygon, Mesh, Union, Difference };
  Type type = Type::Box;

  geometry::Box box;  // Box: min, max (z ignored in 2D)

  // Cylinder: in 3D the axis from p1 to p2 with `radius`; in 2D a disc (center = p1).
  // Sphere: center = p1, radius (a disc in 2D).
  Eigen::Vector3d p1 = Eigen::Vector3d::Zero(), p2 = Eigen::Vector3d::Zero();
  double radius = 0.0;

  std::vector<Eigen::Vector3d> points;  // Polygon (2D only): vertices in order

  // Mesh: a closed triangle mesh (STL ASCII/binary, OBJ, OFF, PLY), path relative to the case
  // file's folder. In a 2D case the (placed) mesh is cut by the plane y = slice_y and the
  // section's (x, z) becomes the 2D (x, y).
  std::string file;
  Placement placement;
  bool repair = false;
  std::optional<double> slice_y;

  // Union: any of children; Difference: children[0] minus every other child.
  std::vector<ShapeSpec> children;

  int line = 0;
};

}  // namespace swell
