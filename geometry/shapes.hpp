// Geometric primitives used to describe bodies, and their signed distance.
//
// Positions are 3-vectors; 2D cases use (x, y) and ignore z. The signed distance is negative
// inside the shape and positive outside. For boxes it is the Chebyshev (max-norm) distance, so
// layers of boundary particles around a box fill its corners, as tank walls should.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

namespace swell::geometry {

struct Box {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();

  // Signed max-norm distance to the box surface over the first `dim` axes.
  double signed_distance(const Eigen::Vector3d& p, int dim) const {
    double outside = -std::numeric_limits<double>::infinity();
    for (int d = 0; d < dim; ++d) {
      const double c = 0.5 * (min[d] + max[d]);
      const double half = 0.5 * (max[d] - min[d]);
      outside = std::max(outside, std::abs(p[d] - c) - half);
    }
    return outside;
  }
  bool contains(const Eigen::Vector3d& p, int dim) const { return signed_distance(p, dim) < 0.0; }
  double volume(int dim) const {
    double v = 1.0;
    for (int d = 0; d < dim; ++d) v *= (max[d] - min[d]);
    return v;
  }
};

}  // namespace swell::geometry
