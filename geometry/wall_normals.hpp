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
std::vector<Eigen::Vector3d> wall_normals(const BodyGeometry& body,
                                          const std::vector<Eigen::Vector3d>& points,
                                          const FillOptions& opt);

}  // namespace swell::geometry
