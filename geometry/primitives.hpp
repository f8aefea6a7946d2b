// Shape implementations for the case-file primitives (box, cylinder, sphere, polygon) and for
// CSG (union, difference). Meshes are geometry/mesh_solid.hpp; build_shape
// (geometry/shape_factory.hpp) turns a ShapeSpec into any of them.
//
// All signed distances are 1-Lipschitz and never larger in magnitude than the true Euclidean
// distance to the surface (exact for cylinder, sphere and polygon; max-norm for the box; the
// usual min/max bounds for CSG). The lattice fill relies on this to skip along rows.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/shape.hpp"
#include "geometry/shapes.hpp"

namespace swell::geometry {

// Axis-aligned box over the first `dim` axes, with the max-norm signed distance of
// geometry::Box, so wall layers around it fill its corners.
class BoxShape : public Shape {
 public:
  BoxShape(const Eigen::Vector3d& min, const Eigen::Vector3d& max, int dim);
  double signed_distance(const Eigen::Vector3d& p) const override;
  Eigen::Vector3d closest_surface_point(const Eigen::Vector3d& p) const override;
  bool contains(const Eigen::Vector3d& p) const override;
  Aabb bounds() const override;
  double volume() const override;
  std::string describe() const override;
  const Box& box() const { return box_; }
  // The nearest point on the faces not listed in `open` (bit 2 d: the min face of axis d,
  // bit 2 d + 1: the max face), e.g. the walls of a tank with an open top.
  Eigen::Vector3d closest_point_on_faces(const Eigen::Vector3d& p, unsigned open) const;
  int dim() const { return dim_; }

 private:
  Box box_;
  int dim_;
};

// 3D: the finite cylinder of `radius` around the segment p1-p2, flat caps (exact Euclidean
// distance, caps and rims included). 2D: the disc of `radius` centred at p1 (p2 unused).
class CylinderShape : public Shape {
 public:
  CylinderShape(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, double radius, int dim);
  double signed_distance(const Eigen::Vector3d& p) const override;
  Eigen::Vector3d closest_surface_point(const Eigen::Vector3d& p) const override;
  Aabb bounds() const override;
  double volume() const override;
  std::string describe() const override;

 private:
  Eigen::Vector3d p1_, p2_, axis_;  // axis_: unit vector p1 -> p2 (3D)
  double radius_, length_;
  int dim_;
};

// Ball (3D) or disc (2D).
class SphereShape : public Shape {
 public:
  SphereShape(const Eigen::Vector3d& center, double radius, int dim);
  double signed_distance(const Eigen::Vector3d& p) const override;
  Eigen::Vector3d closest_surface_point(const Eigen::Vector3d& p) const override;
  Aabb bounds() const override;
  double volume() const override;
  std::string describe() const override;

 private:
  Eigen::Vector3d center_;
  double radius_;
  int dim_;
};

// A 2D region bounded by one or more closed loops (the last vertex joins the first), with the
// even-odd rule: a point is inside when a ray from it crosses the loops an odd number of times.
// One loop is a simple polygon; several loops represent a section with holes (a mesh cut).
// Distance is exact (nearest edge). Edges are binned on a uniform grid (distance: search in
// growing rings of cells) and in horizontal slabs (inside test), so large loops stay cheap.
class PolygonShape : public Shape {
 public:
  explicit PolygonShape(std::vector<std::vector<Eigen::Vector2d>> loops,
                        std::string description = "polygon");
  double signed_distance(const Eigen::Vector3d& p) const override;
  Eigen::Vector3d closest_surface_point(const Eigen::Vector3d& p) const override;
  bool contains(const Eigen::Vector3d& p) const override;
  Aabb bounds() const override;
  // Shoelace area with the even-odd rule for non-crossing loops: each loop counts + or -
  // by the parity of the number of other loops around it.
  double volume() const override;
  std::string describe() const override;
  const std::vector<std::vector<Eigen::Vector2d>>& loops() const { return loops_; }

 private:
  double unsigned_distance(const Eigen::Vector2d& q) const;
  Eigen::Vector2d nearest_edge_point(const Eigen::Vector2d& q) const;
  bool inside(const Eigen::Vector2d& q) const;

  struct Edge {
    Eigen::Vector2d a, b;
  };
  std::vector<std::vector<Eigen::Vector2d>> loops_;
  std::string description_;
  std::vector<Edge> edges_;
  Eigen::Vector2d lo_, hi_;
  // Distance grid: cells of size cell_, CSR lists of edge indices.
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> cell_start_, cell_edges_;
  // Inside test: horizontal slabs of height slab_, CSR lists of edge indices.
  double slab_ = 1.0;
  int nslab_ = 1;
  std::vector<int> slab_start_, slab_edges_;
  double area_ = 0.0;
};

// Points in any child. Distance: min of the children's (exact outside, a lower bound of the
// depth inside). Volume: the sum when the children's bounding boxes are disjoint, else NaN.
class UnionShape : public Shape {
 public:
  explicit UnionShape(std::vector<ShapePtr> children);
  double signed_distance(const Eigen::Vector3d& p) const override;
  Eigen::Vector3d closest_surface_point(const Eigen::Vector3d& p) const override;
  bool contains(const Eigen::Vector3d& p) const override;
  Aabb bounds() const override { return bounds_; }
  double volume() const override;
  std::string describe() const override;

 private:
  std::vector<ShapePtr> children_;
  Aabb bounds_;
};

// Points of `base` in none of `cut`. Distance: max(d_base, -d_cut...). Volume: base's when no
// cut's bounding box meets base's, else NaN.
class DifferenceShape : public Shape {
 public:
  DifferenceShape(ShapePtr base, std::vector<ShapePtr> cut);
  double signed_distance(const Eigen::Vector3d& p) const override;
  Eigen::Vector3d closest_surface_point(const Eigen::Vector3d& p) const override;
  bool contains(const Eigen::Vector3d& p) const override;
  Aabb bounds() const override { return base_->bounds(); }
  double volume() const override;
  std::string describe() const override;

 private:
  ShapePtr base_;
  std::vector<ShapePtr> cut_;
};

// "(x, y)" or "(x, y, z)", 6 significant digits, for messages.
std::string format_point(const Eigen::Vector3d& v, int dim);

// True when the boxes overlap (touching counts as overlapping).
bool overlaps(const Aabb& a, const Aabb& b);

}  // namespace swell::geometry
