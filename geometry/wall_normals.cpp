#include "geometry/wall_normals.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
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

// Directions to march along: evenly spaced angles (2D), a Fibonacci sphere (3D).
std::vector<Eigen::Vector3d> directions(int dim) {
  std::vector<Eigen::Vector3d> out;
  if (dim == 2) {
    constexpr int kN = 90;  // 4 degrees apart
    for (int k = 0; k < kN; ++k) {
      const double a = 2.0 * M_PI * k / kN;
      out.emplace_back(std::cos(a), std::sin(a), 0.0);
    }
    return out;
  }
  constexpr int kN = 42;  // ~30 degrees apart
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < kN; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / kN, r = std::sqrt(1.0 - z * z);
    out.emplace_back(r * std::cos(golden * k), r * std::sin(golden * k), z);
  }
  return out;
}

// The distance along unit direction d from x to where it enters the region (infinity if not
// within about `reach`; the caller compares): steps of the region's depth, a lower bound of
// the distance to it (never into it by more than `fine`), then bisection to `fine` / 1024.
double entry_distance(const FluidRegion& region, const Eigen::Vector3d& x, const Eigen::Vector3d& d,
                      double reach, double fine, double tol) {
  double t = 0.0;
  // Up to one fine step past reach: the last step may straddle it.
  // Inside: depth < -tol (one signed distance per body and step; open faces do not matter
  // this close to a wall).
  for (int it = 0; it < 400 && t <= reach + fine; ++it) {
    const double phi = region.depth(x + t * d);
    if (t > 0.0 && phi < -tol) {
      double lo = std::max(0.0, t - fine), hi = t;
      for (int b = 0; b < 10; ++b) {
        const double mid = 0.5 * (lo + hi);
        (region.depth(x + mid * d) < -tol ? hi : lo) = mid;
      }
      return hi;
    }
    t += std::max(phi, fine);
  }
  return std::numeric_limits<double>::infinity();
}

// The shortest entry into the region from x within reach: the best of the direction set, then
// a local refinement (halving the angular step). Zero vector if none.
Eigen::Vector3d wetted_normal(const FluidRegion& region, const Eigen::Vector3d& x,
                              const std::vector<Eigen::Vector3d>& dirs, int dim, double reach,
                              double dp, double tol) {
  const double fine = 0.01 * dp;
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d bd = Eigen::Vector3d::Zero();
  for (const auto& d : dirs) {
    const double t = entry_distance(region, x, d, std::min(best, reach), fine, tol);
    if (t < best) best = t, bd = d;
  }
  if (!std::isfinite(best)) return Eigen::Vector3d::Zero();
  // Refine: rotate the direction by +-step about axes orthogonal to it.
  double step = dim == 2 ? 2.0 * M_PI / 90.0 : 0.5;
  for (int it = 0; it < 40; ++it) {
    // The directions orthogonal to bd to turn towards: one in 2D, two in 3D.
    const Eigen::Vector3d u =
        dim == 2 ? Eigen::Vector3d(-bd.y(), bd.x(), 0.0) : Eigen::Vector3d(bd.unitOrthogonal());
    const Eigen::Vector3d v = bd.cross(u);
    bool moved = false;
    for (int k = 0; k < (dim == 2 ? 2 : 4); ++k) {
      const Eigen::Vector3d side = (k % 2 ? -1.0 : 1.0) * (k < 2 ? u : v);
      const Eigen::Vector3d d = (std::cos(step) * bd + std::sin(step) * side).normalized();
      const double t = entry_distance(region, x, d, best, fine, tol);
      if (t < best) best = t, bd = d, moved = true;
    }
    if (!moved) step *= 0.5;
  }
  Eigen::Vector3d n = best * bd;
  if (dim == 2) n.z() = 0.0;
  return n;
}

}  // namespace

FluidRegion::FluidRegion(const std::vector<BodyGeometry>& bodies, int dim) : dim_(dim) {
  for (const auto& b : bodies) {
    if (b.fluid || !b.shape) continue;
    if (b.walls_inside)
      tanks_.push_back({b.shape.get(), dynamic_cast<const BoxShape*>(b.shape.get())
                                           ? open_face_bits(b.open)
                                           : 0u});
    else
      structures_.push_back({b.shape.get(), b.shape->bounds()});
  }
}

double FluidRegion::box_distance(const Aabb& b, const Eigen::Vector3d& x) const {
  double s = 0.0;
  for (int d = 0; d < dim_; ++d) {
    const double g = std::max({b.min[d] - x[d], x[d] - b.max[d], 0.0});
    s += g * g;
  }
  return std::sqrt(s);
}

bool FluidRegion::contains(const Eigen::Vector3d& x, double tol) const {
  for (const Structure& s : structures_)
    if (!(box_distance(s.box, x) > tol) && !(s.shape->signed_distance(x) > tol)) return false;
  if (tanks_.empty()) return true;
  for (const Tank& t : tanks_) {
    if (!t.open) {
      if (t.shape->signed_distance(x) < -tol) return true;
      continue;
    }
    const Aabb box = t.shape->bounds();
    bool in = true;
    for (int d = 0; d < dim_ && in; ++d) {
      in = in && ((t.open & (1u << (2 * d))) || x[d] > box.min[d] + tol);
      in = in && ((t.open & (1u << (2 * d + 1))) || x[d] < box.max[d] - tol);
    }
    if (in) return true;
  }
  return false;
}

double FluidRegion::depth(const Eigen::Vector3d& x) const {
  double phi = -std::numeric_limits<double>::infinity();
  for (const Structure& s : structures_) {
    // Outside its box the structure adds at most -(box distance) < phi's other terms often.
    const double gap = box_distance(s.box, x);
    phi = std::max(phi, gap > 0.0 ? -gap : -s.shape->signed_distance(x));
  }
  if (!tanks_.empty()) {
    double out = std::numeric_limits<double>::infinity();
    for (const Tank& t : tanks_) out = std::min(out, t.shape->signed_distance(x));
    phi = std::max(phi, out);
  }
  return phi;
}

std::vector<Eigen::Vector3d> wall_normals(const BodyGeometry& body,
                                          const std::vector<Eigen::Vector3d>& points,
                                          const FillOptions& opt,
                                          const std::vector<BodyGeometry>* bodies) {
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
  std::optional<FluidRegion> region;
  if (bodies) region.emplace(*bodies, opt.dim);
  const std::vector<Eigen::Vector3d> dirs =
      bodies ? directions(opt.dim) : std::vector<Eigen::Vector3d>{};
#pragma omp parallel for schedule(dynamic, 256)
  for (long k = 0; k < static_cast<long>(points.size()); ++k) {
    const Eigen::Vector3d& x = points[static_cast<std::size_t>(k)];
    const Eigen::Vector3d q =
        box && open ? box->closest_point_on_faces(x, open) : shape.closest_surface_point(x);
    Eigen::Vector3d n = q - x;
    if (opt.dim == 2) n.z() = 0.0;
    // A ghost outside the fluid region (a face resting on another body): the wetted surface's
    // nearest point instead, if within reach.
    if (region && n.norm() > tol && !region->contains(x + 2.0 * n, tol)) {
      const Eigen::Vector3d w = wetted_normal(*region, x, dirs, opt.dim, reach, dp, tol);
      if (w.norm() > tol && w.norm() <= reach && region->contains(x + 2.0 * w, tol)) n = w;
    }
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
            (body.walls_inside
                 ? " falls outside the tank (is the tank narrower than twice its wall layers, "
                   "or the mesh not closed?)"
                 : " falls inside the solid (is the body thinner than twice its wall layers, or "
                   "the mesh not closed?)");
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
