// The shape interface every body geometry implements: primitives (box, cylinder, sphere,
// polygon), CSG (union, difference) and triangle meshes read from STL/OBJ/OFF/PLY.
//
// Shapes are queried only while particles are created (never in the time loop), so a virtual
// interface is fine here. Points are 3-vectors; a 2D shape lives in the z = 0 plane and
// ignores z.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>

namespace swell::geometry {

// Coordinates geometry may reach, in metres from the origin
// (docs/user-guide/case-files.md#shapes): far beyond any coastal model, and small enough that
// lattice indices and CGAL's arithmetic stay well inside their ranges. Mesh vertices beyond it
// are refused at load, other shapes at the fill.
inline constexpr double kMaxCoordinate = 1.0e6;

struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  void extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
};

class Shape {
 public:
  virtual ~Shape() = default;
  // Signed distance to the surface: negative inside, positive outside. Exact (Euclidean) for
  // curved shapes and meshes; boxes use the max-norm distance so wall layers fill corners.
  // CSG results are the usual min/max combinations (exact sign, distance exact near the
  // surface of one operand). Wall layers and fluid gaps only use it within a few dp.
  virtual double signed_distance(const Eigen::Vector3d& p) const = 0;
  virtual bool contains(const Eigen::Vector3d& p) const { return signed_distance(p) < 0.0; }
  // The point of the surface nearest to p in the Euclidean norm (for 2D shapes, in the z = 0
  // plane). Used for mDBC's wall normals and ghost nodes (geometry/wall_normals.hpp): exact
  // for primitives and meshes; for CSG the nearest operand point that lies on the result's
  // surface (exact unless the result's surface near p is a part of an operand's surface that
  // is not that operand's nearest).
  virtual Eigen::Vector3d closest_surface_point(const Eigen::Vector3d& p) const = 0;
  // Bounding box of the shape (for 2D shapes, z of both corners is 0).
  virtual Aabb bounds() const = 0;
  // Exact volume (area in 2D) where known, NaN otherwise.
  virtual double volume() const { return std::numeric_limits<double>::quiet_NaN(); }
  // Short description for reports, e.g. "box", "mesh tank.stl (1204 faces)".
  virtual std::string describe() const = 0;
};

using ShapePtr = std::shared_ptr<const Shape>;

}  // namespace swell::geometry
