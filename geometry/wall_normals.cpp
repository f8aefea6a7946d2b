#include "geometry/wall_normals.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geometry/primitives.hpp"

namespace swell::geometry {
namespace {

// Bit 2 d (+1) for the min (max) face of axis d, from the names xmin ... zmax.
unsigned open_face_bits(const std::vector<std::string>& open) {
  unsigned bits = 0;
  for (const auto& f : open) {
    if (f.size() != 4) continue;
    const int axis = f[0] - 'x';
    if (axis < 0 || axis > 2) continue;
    bits |= 1u << (2 * axis + (f.substr(1) == "max" ? 1 : 0));
  }
  return bits;
}

}  // namespace

std::vector<Eigen::Vector3d> wall_normals(const BodyGeometry& body,
                                          const std::vector<Eigen::Vector3d>& points,
                                          const FillOptions& opt) {
  if (body.fluid || !body.shape)
    throw std::invalid_argument("wall_normals: '" + body.name + "' is not a boundary body");
  const Shape& shape = *body.shape;
  const auto* box = dynamic_cast<const BoxShape*>(&shape);
  const unsigned open = body.walls_inside ? open_face_bits(body.open) : 0u;
  const double dp = opt.dp;
  // Wall points lie within `layers` dp of the surface (plus the lattice's half-spacing on a
  // diagonal); the ghost must be on the fluid side by more than rounding.
  const double reach = (body.layers + 1.0) * dp * std::sqrt(static_cast<double>(opt.dim));
  const double tol = 1e-6 * dp;
  std::vector<Eigen::Vector3d> out(points.size());
  std::string error;
#pragma omp parallel for schedule(dynamic, 256)
  for (long k = 0; k < static_cast<long>(points.size()); ++k) {
    const Eigen::Vector3d& x = points[static_cast<std::size_t>(k)];
    const Eigen::Vector3d q =
        box && open ? box->closest_point_on_faces(x, open) : shape.closest_surface_point(x);
    Eigen::Vector3d n = q - x;
    if (opt.dim == 2) n.z() = 0.0;
    out[static_cast<std::size_t>(k)] = n;
    const Eigen::Vector3d ghost = x + 2.0 * n;
    const double sd = shape.signed_distance(ghost);
    const bool fluid_side = body.walls_inside ? sd <= tol : sd >= -tol;
    std::string why;
    if (!n.allFinite())
      why = "no nearest surface point";
    else if (n.norm() > reach)
      why = "it lies " + std::to_string(n.norm() / dp) + " dp from the surface, beyond its " +
            std::to_string(body.layers) + " wall layers";
    else if (!fluid_side && n.norm() > tol)
      why = "its ghost node " + format_point(ghost, opt.dim) +
            " falls inside the solid (is the body thinner than twice its wall layers, or "
            "the mesh not closed?)";
    if (!why.empty()) {
#pragma omp critical(swell_wall_normals)
      if (error.empty())
        error = "boundary body '" + body.name + "': cannot compute the mDBC normal of the wall " +
                "particle at " + format_point(x, opt.dim) + ": " + why;
    }
  }
  if (!error.empty()) throw std::invalid_argument(error);
  return out;
}

}  // namespace swell::geometry
