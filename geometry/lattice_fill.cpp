#include "geometry/lattice_fill.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace swell::geometry {
namespace {

// True when the point lies beyond an open face of the box (no wall particles there).
bool beyond_open_face(const BodyGeometry& b, const Eigen::Vector3d& p) {
  static const std::array<const char*, 3> axes = {"x", "y", "z"};
  for (const auto& face : b.open) {
    for (int d = 0; d < 3; ++d) {
      if (face == std::string(axes[d]) + "min" && p[d] < b.box.min[d]) return true;
      if (face == std::string(axes[d]) + "max" && p[d] > b.box.max[d]) return true;
    }
  }
  return false;
}

// Is p part of the wall of boundary body b?
bool in_wall(const BodyGeometry& b, const Eigen::Vector3d& p, int dim, double dp) {
  const double sd = b.box.signed_distance(p, dim);
  const double thickness = b.layers * dp * (1.0 + 1e-9);
  if (b.walls_inside) return sd > 0.0 && sd <= thickness && !beyond_open_face(b, p);
  return sd < 0.0 && sd >= -thickness;
}

// Is p free for fluid with respect to boundary body b (not in its solid side, not too close)?
bool clear_of(const BodyGeometry& b, const Eigen::Vector3d& p, int dim, double gap) {
  const double sd = b.box.signed_distance(p, dim);
  const double tol = 1e-9 * (gap > 0.0 ? gap : 1.0);
  if (b.walls_inside) return sd <= -gap + tol;
  return sd >= gap - tol;
}

template <class Fn>
void for_lattice_points(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int dim, double dp,
                        Fn&& fn) {
  std::array<long, 3> i0{0, 0, 0}, i1{0, 0, 0};
  for (int d = 0; d < dim; ++d) {
    i0[d] = static_cast<long>(std::floor(lo[d] / dp - 0.5)) - 1;
    i1[d] = static_cast<long>(std::ceil(hi[d] / dp - 0.5)) + 1;
  }
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (long k = i0[2]; k <= i1[2]; ++k) {
    if (dim == 3) p.z() = (k + 0.5) * dp;
    for (long j = i0[1]; j <= i1[1]; ++j) {
      p.y() = (j + 0.5) * dp;
      for (long i = i0[0]; i <= i1[0]; ++i) {
        p.x() = (i + 0.5) * dp;
        fn(p);
      }
    }
  }
}

}  // namespace

std::vector<FilledBody> fill_bodies(const std::vector<BodyGeometry>& bodies,
                                    const FillOptions& opt) {
  if (!(opt.dp > 0.0)) throw std::invalid_argument("fill_bodies: dp must be positive");
  const int dim = opt.dim;
  const double dp = opt.dp, gap = opt.gap_factor * dp;
  std::vector<FilledBody> out;
  for (std::size_t bi = 0; bi < bodies.size(); ++bi) {
    const BodyGeometry& b = bodies[bi];
    FilledBody fb{b.name, b.fluid, {}};
    Eigen::Vector3d lo = b.box.min, hi = b.box.max;
    if (!b.fluid && b.walls_inside) {
      lo.array() -= b.layers * dp;
      hi.array() += b.layers * dp;
    }
    for_lattice_points(lo, hi, dim, dp, [&](const Eigen::Vector3d& p) {
      if (!b.fluid) {
        if (in_wall(b, p, dim, dp)) fb.points.push_back(p);
        return;
      }
      if (!b.box.contains(p, dim)) return;
      for (const auto& other : bodies)
        if (!other.fluid && !clear_of(other, p, dim, gap)) return;
      for (std::size_t e = 0; e < bi; ++e)  // earlier fluid bodies keep shared points
        if (bodies[e].fluid && bodies[e].box.contains(p, dim)) return;
      fb.points.push_back(p);
    });
    if (fb.points.empty())
      throw std::invalid_argument("body '" + b.name +
                                  "' holds no particle at dp = " + std::to_string(dp) +
                                  " (is it thinner than dp, or inside a wall?)");
    out.push_back(std::move(fb));
  }
  return out;
}

}  // namespace swell::geometry
