#include "geometry/fill_volume.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace swell::geometry {

StructureOverlap structures_in_region(const std::vector<BodyGeometry>& bodies, std::size_t fluid,
                                      int dim, double dp, int refine, double max_points) {
  if (fluid >= bodies.size() || !bodies[fluid].fluid)
    throw std::invalid_argument("structures_in_region: body index is not a fluid body");
  if (!(dp > 0.0) || refine < 1 || (dim != 2 && dim != 3))
    throw std::invalid_argument("structures_in_region: needs dp > 0, refine >= 1, dim 2 or 3");
  const BodyGeometry& body = bodies[fluid];
  const int up = dim - 1;
  const Shape* region = body.shape.get();
  if (body.fill_below) {
    if (body.container < 0 || body.container >= static_cast<int>(bodies.size()))
      throw std::invalid_argument("structures_in_region: fill_below without a container");
    region = bodies[static_cast<std::size_t>(body.container)].shape.get();
  }
  if (!region) throw std::invalid_argument("structures_in_region: the fluid body has no region");
  Aabb rb = region->bounds();
  if (body.fill_below) rb.max[up] = std::min(rb.max[up], *body.fill_below);

  // The structures, and the part of the region's bounds they can reach.
  std::vector<const Shape*> structures;
  Aabb scan;
  bool any = false;
  for (const BodyGeometry& b : bodies) {
    if (b.fluid || b.walls_inside || !b.shape) continue;
    const Aabb sb = b.shape->bounds();
    Aabb cut;
    bool empty = false;
    for (int d = 0; d < dim; ++d) {
      cut.min[d] = std::max(sb.min[d], rb.min[d]);
      cut.max[d] = std::min(sb.max[d], rb.max[d]);
      empty = empty || !(cut.max[d] > cut.min[d]);
    }
    if (empty) continue;
    structures.push_back(b.shape.get());
    if (!any) {
      scan = cut;
      any = true;
    } else {
      for (int d = 0; d < dim; ++d) {
        scan.min[d] = std::min(scan.min[d], cut.min[d]);
        scan.max[d] = std::max(scan.max[d], cut.max[d]);
      }
    }
  }
  StructureOverlap out;
  if (!any) return out;

  // Index ranges of the counting lattice; coarser if the scan box would hold too many points.
  long lo[3] = {0, 0, 0}, n[3] = {1, 1, 1};
  double s = dp / refine;
  for (;;) {
    double total = 1.0;
    for (int d = 0; d < dim; ++d) {
      lo[d] = static_cast<long>(std::floor(scan.min[d] / s));
      n[d] = static_cast<long>(std::ceil(scan.max[d] / s)) - lo[d];
      total *= static_cast<double>(n[d]);
    }
    if (total <= max_points || refine == 1) break;
    refine = std::max(1, refine / 2);
    s = dp / refine;
  }

  const bool below = body.fill_below.has_value();
  const double level = below ? *body.fill_below : 0.0;
  const long rows = n[1] * n[2];
  std::size_t count = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : count)
  for (long r = 0; r < rows; ++r) {
    Eigen::Vector3d p(0.0, (lo[1] + r % n[1] + 0.5) * s,
                      dim == 3 ? (lo[2] + r / n[1] + 0.5) * s : 0.0);
    if (below && !(p[up] < level)) continue;
    for (long i = 0; i < n[0]; ++i) {
      p.x() = (lo[0] + i + 0.5) * s;
      if (below && !(p[up] < level)) continue;
      bool solid = false;
      for (const Shape* st : structures) {
        if (st->contains(p)) {
          solid = true;
          break;
        }
      }
      if (solid && region->contains(p)) ++count;
    }
  }
  out.points = count;
  out.spacing = s;
  out.volume = static_cast<double>(count) * std::pow(s, dim);
  return out;
}

}  // namespace swell::geometry
