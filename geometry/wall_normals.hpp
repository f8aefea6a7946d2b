// Wall normals for mDBC (bc/mdbc.hpp), computed from the geometry, never given by the user.
//
// A wall particle's normal vector is the vector from the particle to the nearest point of its
// boundary body's surface (Shape::closest_surface_point, Euclidean): its direction is the wall
// normal pointing into the fluid, its length the particle's distance to the wall, so the ghost
// node pos + 2 normal is the particle mirrored across the wall. At a tank's corner the nearest
// point is the corner itself and the ghost lies on the diagonal; open faces of a box tank are
// left out of the nearest-point search (the walls below an open top mirror sideways, not up).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "geometry/lattice_fill.hpp"

namespace swell::geometry {

// The normal vector of each of a boundary body's wall points (same order). Throws
// std::invalid_argument naming the body and the point where a ghost node would not lie on
// the fluid side of the body's surface (e.g. a shell thinner than its wall layers), or where a
// point lies farther from the surface than its wall layers reach.
//
// `bodies` (the case's bodies, `body` among them; optional): the fluid region they bound is
// inside a tank (a body with walls inside; beyond an open face of a box counts as inside) and
// outside every structure (walls outside). Where a point's nearest surface point is a face
// the fluid never reaches (a face resting on another body: a beach on the tank floor, a
// caisson on its berm), its ghost node falls outside that region and the wall would read dry
// next to water. Such a point gets instead the vector to the nearest point of the fluid
// region's boundary (the wetted surface) if one lies within its wall layers' reach: found by
// marching rays from the point in a set of directions (90 in 2D, 42 in 3D) until they enter
// the region (steps bounded below by the signed distances), then turning the shortest one by
// halving angles until it is shortest to 1e-3 degrees. A point whose wetted surface lies
// within reach only in a cone narrower than the directions' spacing keeps its own normal.
// Every other point keeps its own surface's nearest point.
std::vector<Eigen::Vector3d> wall_normals(const BodyGeometry& body,
                                          const std::vector<Eigen::Vector3d>& points,
                                          const FillOptions& opt,
                                          const std::vector<BodyGeometry>* bodies = nullptr);

// The fluid region the case's boundary bodies bound (see wall_normals).
class FluidRegion {
 public:
  FluidRegion(const std::vector<BodyGeometry>& bodies, int dim);
  // Whether x lies in the region by more than tol from its boundary.
  bool contains(const Eigen::Vector3d& x, double tol) const;
  // A lower bound of the distance from x to the region (<= 0 inside; open faces ignored).
  double depth(const Eigen::Vector3d& x) const;

 private:
  struct Tank {
    const Shape* shape;
    unsigned open;  // open faces of a box tank (bit 2 axis + side)
  };
  struct Structure {
    const Shape* shape;
    Aabb box;  // its bounds: beyond them its signed distance is at least the box distance
  };
  // The Euclidean distance from x to the box over the first dim axes (0 inside).
  double box_distance(const Aabb& b, const Eigen::Vector3d& x) const;
  std::vector<Tank> tanks_;
  std::vector<Structure> structures_;
  int dim_;
};

}  // namespace swell::geometry
