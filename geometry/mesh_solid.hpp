// A closed triangle mesh (STL ASCII or binary, OBJ, OFF, PLY) read with CGAL and used as a
// solid: inside/outside by ray casting on an AABB tree (CGAL Side_of_triangle_mesh), signed
// distance from AABB-tree distance queries, volume from CGAL::Polygon_mesh_processing.
//
// The CGAL types stay in mesh_solid.cpp (pimpl) so including this header stays cheap.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/shape.hpp"
#include "geometry/shape_spec.hpp"

namespace swell::geometry {

// A mesh that cannot be used; the message names the file, the check that failed and counts.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What loading a mesh found and changed, for the fill report.
struct MeshReport {
  std::string file;
  std::size_t vertices = 0, faces = 0;
  bool closed = false;
  std::size_t border_edges = 0;        // before repair
  std::size_t self_intersections = 0;  // pairs of intersecting faces, before repair
  bool reoriented = false;             // normals pointed inward and were flipped
  std::vector<std::string> repairs;    // what repair: true changed, one line each
  double volume = 0.0;                 // after placement [m^3]
};

class MeshSolid : public Shape {
 public:
  // Reads `path`, applies the placement (scale, rotate x-y-z in degrees, translate), checks it
  // is closed, free of self-intersections and consistently oriented (orienting it outward if
  // needed). A hole or a self-intersection throws MeshError unless `repair` is set, in which
  // case CGAL's soup repair, stitching, hole filling and self-intersection removal run and
  // are listed in report->repairs; a mesh still broken after repair throws too.
  static std::shared_ptr<MeshSolid> load(const std::string& path, const Placement& placement,
                                         bool repair, MeshReport* report = nullptr);
  ~MeshSolid() override;

  // Every const member below only reads structures built by load(), so all of them may be
  // called concurrently (OpenMP threads) on one MeshSolid. contains() counts points on the
  // surface as inside.

  // Exact Euclidean distance to the nearest face (AABB tree), sign by ray casting. Its cost
  // grows with the distance to the surface (deep inside a finely meshed sphere every face is
  // nearly equidistant); use signed_distance_within() where only a band matters.
  double signed_distance(const Eigen::Vector3d& p) const override;
  // The same where |distance| <= max_distance, else +-max_distance with the exact sign; much
  // cheaper away from the surface (wall layers and fluid gaps need only a few dp).
  double signed_distance_within(const Eigen::Vector3d& p, double max_distance) const;
  // signed_distance() through CGAL's AABB_tree::squared_distance() (reference for tests).
  double signed_distance_cgal(const Eigen::Vector3d& p) const;
  bool contains(const Eigen::Vector3d& p) const override;
  // The nearest point of the mesh surface (AABB tree closest-point query).
  Eigen::Vector3d closest_surface_point(const Eigen::Vector3d& p) const override;
  Aabb bounds() const override;
  double volume() const override;
  std::string describe() const override;

  // Cross-section by the plane y = y0: closed loops of (x, z) points (outer boundaries and
  // holes alike; use the even-odd rule). Empty if the plane misses the mesh.
  std::vector<std::vector<Eigen::Vector2d>> slice_y(double y0) const;

  const MeshReport& report() const;

  struct Impl;

 private:
  explicit MeshSolid(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace swell::geometry
