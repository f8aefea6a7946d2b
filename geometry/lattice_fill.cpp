#include "geometry/lattice_fill.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "geometry/primitives.hpp"

namespace swell::geometry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Lattice index range covering a box padded by `pad` (one extra plane each side against
// rounding); z is {0} in 2D.
struct IndexRange {
  std::array<long, 3> lo{0, 0, 0}, hi{0, 0, 0};
};

IndexRange index_range(const Aabb& b, double pad, int dim, double dp) {
  IndexRange r;
  for (int d = 0; d < dim; ++d) {
    if (!std::isfinite(b.min[d]) || !std::isfinite(b.max[d]))
      throw std::invalid_argument("fill: a shape has no finite bounds");
    // Lattice indices are longs: keep (x / dp) far inside their range before converting.
    const double reach = std::max(std::abs(b.min[d] - pad), std::abs(b.max[d] + pad)) / dp;
    if (!(reach < 1e15))
      throw std::invalid_argument("fill: a shape reaches " + std::to_string(reach) +
                                  " dp from the origin (more than 1e15 lattice planes)");
    r.lo[d] = static_cast<long>(std::floor((b.min[d] - pad) / dp - 0.5)) - 1;
    r.hi[d] = static_cast<long>(std::ceil((b.max[d] + pad) / dp - 0.5)) + 1;
  }
  return r;
}

// Max-norm distance from p to the box over the first dim axes (0 inside).
double box_gap(const Aabb& b, const Eigen::Vector3d& p, int dim) {
  double g = 0.0;
  for (int d = 0; d < dim; ++d) g = std::max({g, b.min[d] - p[d], p[d] - b.max[d]});
  return g;
}

// One shape test along a lattice row: is p on the required side of the surface
// (Shape::contains, cheap even for meshes) and does its signed distance lie in [lo, hi]
// (infinite ends: no condition, and no distance query at all)? The signed distance is
// 1-Lipschitz, so after a value v the answer cannot change for the next
// floor((distance from v to the nearest of lo, hi, 0) / dp) points of the row; those reuse it
// (march). Rounding is covered by a margin of 1e-6 dp. Distance queries deep inside a mesh are
// its most expensive ones (many faces at similar distances), hence the side test first.
class RowTest {
 public:
  RowTest(const Shape* shape, bool inside, double lo, double hi, double dp, bool march)
      : shape_(shape),
        inside_(inside),
        lo_(lo),
        hi_(hi),
        dp_(dp),
        march_(march),
        side_only_(!std::isfinite(lo) && !std::isfinite(hi)) {}

  // i must not decrease between calls within a row.
  bool operator()(long i, const Eigen::Vector3d& p) {
    if (march_ && i <= valid_until_) return value_;
    if (shape_->contains(p) != inside_) return false;
    if (side_only_) return true;
    const double v = shape_->signed_distance(p);
    value_ = v >= lo_ && v <= hi_ && (inside_ ? v < 0.0 : v > 0.0);
    if (march_) {
      const double room =
          std::min({std::abs(v - lo_), std::abs(v - hi_), std::abs(v)}) - 1e-6 * dp_;
      valid_until_ = room > 0.0 ? i + static_cast<long>(std::min(room / dp_, 1e15)) : i;
    }
    return value_;
  }

 private:
  const Shape* shape_;
  bool inside_;
  double lo_, hi_, dp_;
  bool march_, side_only_;
  long valid_until_ = std::numeric_limits<long>::min();
  bool value_ = false;
};

// True when p lies beyond an open face of the body (no wall particles there).
bool beyond_open_face(const std::vector<int>& open_faces, const Aabb& b, const Eigen::Vector3d& p) {
  for (const int f : open_faces) {
    const int d = f / 2;
    if (f % 2 == 0 ? p[d] < b.min[d] : p[d] > b.max[d]) return true;
  }
  return false;
}

// Face names -> 2 * axis + (0: min, 1: max).
std::vector<int> open_face_ids(const BodyGeometry& b, int dim) {
  static const std::array<const char*, 6> names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  std::vector<int> ids;
  for (const auto& face : b.open) {
    const auto it = std::find(names.begin(), names.begin() + 2 * dim, face);
    if (it == names.begin() + 2 * dim)
      throw std::invalid_argument("body '" + b.name + "': unknown open face '" + face + "'");
    ids.push_back(static_cast<int>(it - names.begin()));
  }
  return ids;
}

// Packs lattice indices into one key (21 bits per axis).
std::uint64_t lattice_key(const Eigen::Vector3d& p, double dp) {
  std::uint64_t key = 0;
  for (int d = 0; d < 3; ++d) {
    const long i = std::lround(p[d] / dp - 0.5) + (1L << 20);
    if (i < 0 || i >= (1L << 21))
      throw std::invalid_argument(
          "fill: more than 2^20 lattice planes from the origin; "
          "is dp far too small for the domain?");
    key = (key << 21) | static_cast<std::uint64_t>(i);
  }
  return key;
}

// Everything a row of one body needs, prepared once per body.
struct BodyPlan {
  const BodyGeometry* body = nullptr;
  const Shape* region = nullptr;  // fluid: own shape or container's; wall: own shape
  Aabb region_bounds;             // where its points can be (level applied, walls added)
  Aabb shape_bounds;              // wall: the shape's own bounds (open faces)
  std::optional<double> level;    // fluid below a level
  std::vector<int> open_faces;    // wall
  double thickness = 0.0;         // wall
};

struct Obstacle {  // a boundary body as seen by fluid points
  const Shape* shape;
  Aabb bounds;
  bool walls_inside;
  double reach;  // tanks: beyond this max-norm distance from the bounds, no interaction
};

}  // namespace

// Lattice points (i + 1/2) dp inside [lo, hi] on the first dim axes, as a double.
double lattice_points(const Aabb& b, int dim, double dp) {
  double n = 1.0;
  for (int d = 0; d < dim; ++d) {
    if (!(b.max[d] >= b.min[d])) return 0.0;
    n *= std::floor((b.max[d] - b.min[d]) / dp) + 1.0;
  }
  return n;
}

double BodyFillReport::volume_error(int dim, double dp) const {
  if (!(region_volume > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(in_region) * std::pow(dp, dim) / region_volume - 1.0;
}

FillEstimate estimate_fill(const std::vector<BodyGeometry>& bodies, const FillOptions& opt) {
  if (!(opt.dp > 0.0)) throw std::invalid_argument("fill: dp must be positive");
  const int dim = opt.dim, up = dim - 1;
  const double dp = opt.dp;
  FillEstimate est;
  static const char* const axes[] = {"x", "y", "z"};
  auto checked_bounds = [&](const BodyGeometry& b, const Shape& shape) {
    const Aabb box = shape.bounds();
    for (int d = 0; d < dim; ++d) {
      const double lo = box.min[d], hi = box.max[d];
      if (!std::isfinite(lo) || !std::isfinite(hi))
        throw std::invalid_argument("body '" + b.name + "': its bounds on " + axes[d] +
                                    " are not finite");
      if (std::max(std::abs(lo), std::abs(hi)) > kMaxCoordinate) {
        std::ostringstream m;
        m << "body '" << b.name << "' reaches " << axes[d] << " = "
          << (std::abs(lo) > std::abs(hi) ? lo : hi) << " m; geometry must lie within +-"
          << kMaxCoordinate << " m of the origin (check the units and the placement scale)";
        throw std::invalid_argument(m.str());
      }
    }
    return box;
  };
  for (const BodyGeometry& b : bodies) {
    double n = 0.0;
    if (b.fluid && b.fill_below) {
      if (b.container >= 0 && b.container < static_cast<int>(bodies.size()) &&
          bodies[static_cast<std::size_t>(b.container)].shape) {
        const auto& tank = bodies[static_cast<std::size_t>(b.container)];
        Aabb box = checked_bounds(tank, *tank.shape);
        box.max[up] = std::min(box.max[up], *b.fill_below);
        n = lattice_points(box, dim, dp);
      }
    } else if (b.shape) {
      const Aabb box = checked_bounds(b, *b.shape);
      const double inside = std::isfinite(b.shape->volume()) && b.shape->volume() > 0.0
                                ? b.shape->volume() / std::pow(dp, dim)
                                : std::numeric_limits<double>::quiet_NaN();
      if (b.fluid) {
        n = lattice_points(box, dim, dp);
      } else if (b.walls_inside) {
        Aabb outer = box;
        const double t = std::max(b.layers, 1) * dp;
        for (int d = 0; d < dim; ++d) outer.min[d] -= t, outer.max[d] += t;
        n = lattice_points(outer, dim, dp);
        if (std::isfinite(inside)) n = std::max(0.0, n - 0.999 * inside);
      } else {
        n = lattice_points(box, dim, dp);
        if (std::isfinite(inside)) n = std::min(n, 1.001 * inside + 1.0);
      }
    }
    est.particles.push_back(n);
    est.total += n;
  }
  return est;
}

std::vector<FilledBody> fill_bodies(const std::vector<BodyGeometry>& bodies,
                                    const FillOptions& opt) {
  if (!(opt.dp > 0.0)) throw std::invalid_argument("fill_bodies: dp must be positive");
  if (opt.dim != 2 && opt.dim != 3) throw std::invalid_argument("fill_bodies: dim must be 2 or 3");
  const int dim = opt.dim, up = dim - 1;
  const double dp = opt.dp, gap = opt.gap_factor * dp;
  const double gap_tol = opt.gap_tolerance * dp;
  const char* up_name = dim == 2 ? "y" : "z";
  const std::optional<FillShare>& share = opt.share;
  if (share && (share->axis < 0 || share->axis >= dim))
    throw std::invalid_argument("fill_bodies: the share's axis must be one of the dim axes");

  // Validate and plan every body.
  std::vector<BodyPlan> plans(bodies.size());
  std::vector<Obstacle> obstacles;
  for (std::size_t bi = 0; bi < bodies.size(); ++bi) {
    const BodyGeometry& b = bodies[bi];
    BodyPlan& plan = plans[bi];
    plan.body = &b;
    const std::string who = "body '" + b.name + "'";
    if (b.fluid && b.fill_below) {
      const int c = b.container;
      if (c < 0 || c >= static_cast<int>(bodies.size()) || bodies[c].fluid ||
          !bodies[c].walls_inside || !bodies[c].shape)
        throw std::invalid_argument(who +
                                    ": fill_below needs a container that is a boundary "
                                    "body with walls inside");
      plan.region = bodies[c].shape.get();
      plan.region_bounds = plan.region->bounds();
      plan.region_bounds.max[up] = std::min(plan.region_bounds.max[up], *b.fill_below);
      plan.level = b.fill_below;
      continue;
    }
    if (!b.shape) throw std::invalid_argument(who + " has no shape");
    plan.region = b.shape.get();
    plan.region_bounds = b.shape->bounds();
    if (b.fluid) continue;
    if (b.layers < 1) throw std::invalid_argument(who + ": layers must be at least 1");
    plan.thickness = b.layers * dp * (1.0 + 1e-9);
    plan.shape_bounds = b.shape->bounds();
    if (b.walls_inside) {
      plan.open_faces = open_face_ids(b, dim);
      for (int d = 0; d < dim; ++d) {
        plan.region_bounds.min[d] -= plan.thickness;
        plan.region_bounds.max[d] += plan.thickness;
      }
    }
    obstacles.push_back({b.shape.get(), b.shape->bounds(), b.walls_inside,
                         b.walls_inside ? plan.thickness + gap : 0.0});
  }

  std::vector<FilledBody> out;
  std::unordered_set<std::uint64_t> taken;  // points of earlier fluid bodies
  Aabb taken_bounds;
  for (std::size_t bi = 0; bi < bodies.size(); ++bi) {
    const BodyGeometry& b = bodies[bi];
    const BodyPlan& plan = plans[bi];
    FilledBody fb;
    fb.report.name = b.name;
    fb.report.fluid = b.fluid;
    if (plan.level) {
      std::ostringstream s;
      s << "below " << up_name << " = " << *plan.level << " inside '" << bodies[b.container].name
        << "'";
      fb.report.region = s.str();
      // Known exactly when the container is a box: its cross-section times the depth.
      if (const auto* box = dynamic_cast<const BoxShape*>(plan.region)) {
        const Aabb cb = box->bounds();
        double v = std::max(0.0, std::min(cb.max[up], *plan.level) - cb.min[up]);
        for (int d = 0; d < up; ++d) v *= cb.max[d] - cb.min[d];
        fb.report.region_volume = v;
      }
    } else {
      fb.report.region = b.shape->describe();
      if (b.fluid) fb.report.region_volume = b.shape->volume();
    }

    const IndexRange range = index_range(plan.region_bounds, 0.0, dim, dp);
    const long nj = range.hi[1] - range.lo[1] + 1, nk = range.hi[2] - range.lo[2] + 1;
    const long nrows = std::max(0L, nj) * std::max(0L, nk);
    std::vector<std::vector<Eigen::Vector3d>> rows(static_cast<std::size_t>(nrows));
    std::vector<std::size_t> row_in_region(static_cast<std::size_t>(nrows), 0);
    std::vector<std::uint32_t> row_owned(share ? static_cast<std::size_t>(nrows) : 0, 0);
    const bool check_taken = b.fluid && !taken.empty();
    std::exception_ptr error;

#pragma omp parallel
    {
      // Per-thread tests, reset at each row.
      std::vector<RowTest> clear_tests;
#pragma omp for schedule(dynamic, 4)
      for (long r = 0; r < nrows; ++r) {
        try {
          const long j = range.lo[1] + r % nj, k = range.lo[2] + r / nj;
          Eigen::Vector3d p((range.lo[0] + 0.5) * dp, (j + 0.5) * dp,
                            dim == 3 ? (k + 0.5) * dp : 0.0);
          // Skip the row when it misses the region's bounds.
          bool misses = false;
          for (int d = 1; d < dim; ++d)
            misses = misses || p[d] < plan.region_bounds.min[d] || p[d] > plan.region_bounds.max[d];
          if (misses || (plan.level && !(p[up] < *plan.level))) continue;
          // A share: rows across the share's axis outside its reach are skipped; along a row
          // (axis x) only the indices within reach are visited.
          long i_lo = range.lo[0], i_hi = range.hi[0];
          if (share) {
            if (share->axis != 0 && !share->reaches(p[share->axis])) continue;
            if (share->axis == 0) {
              const double a = (share->lo - share->margin) / dp - 0.5;
              const double z = (share->hi + share->margin) / dp - 0.5;
              if (std::isfinite(a)) i_lo = std::max(i_lo, static_cast<long>(std::floor(a)));
              if (std::isfinite(z)) i_hi = std::min(i_hi, static_cast<long>(std::ceil(z)));
            }
          }
          auto& row = rows[static_cast<std::size_t>(r)];
          std::size_t in_region = 0;
          if (!b.fluid) {
            RowTest wall = b.walls_inside
                               ? RowTest(plan.region, false, 0.0, plan.thickness, dp, opt.march)
                               : RowTest(plan.region, true, -plan.thickness, 0.0, dp, opt.march);
            for (long i = i_lo; i <= i_hi; ++i) {
              p.x() = (i + 0.5) * dp;
              if (share && share->axis == 0 && !share->reaches(p.x())) continue;
              if (box_gap(plan.region_bounds, p, dim) > 0.0) continue;
              if (!plan.open_faces.empty() &&
                  beyond_open_face(plan.open_faces, plan.shape_bounds, p))
                continue;
              if (wall(i, p)) row.push_back(p);
            }
          } else {
            RowTest inside(plan.region, true, -kInf, kInf, dp, opt.march);
            clear_tests.clear();
            for (const auto& o : obstacles)
              clear_tests.push_back(
                  o.walls_inside ? RowTest(o.shape, true, -kInf, -gap + gap_tol, dp, opt.march)
                                 : RowTest(o.shape, false, gap - gap_tol, kInf, dp, opt.march));
            for (long i = i_lo; i <= i_hi; ++i) {
              p.x() = (i + 0.5) * dp;
              if (share && share->axis == 0 && !share->reaches(p.x())) continue;
              if (box_gap(plan.region_bounds, p, dim) > 0.0 || !inside(i, p)) continue;
              if (!share || share->owns(p)) ++in_region;
              bool keep = true;
              for (std::size_t o = 0; keep && o < obstacles.size(); ++o) {
                const Obstacle& ob = obstacles[o];
                const double g = box_gap(ob.bounds, p, dim);
                if (ob.walls_inside ? g > ob.reach : g >= gap - gap_tol) continue;  // far away
                keep = clear_tests[o](i, p);
              }
              if (keep && check_taken && box_gap(taken_bounds, p, dim) <= 0.0)
                keep = !taken.count(lattice_key(p, dp));
              if (keep) row.push_back(p);
            }
          }
          row_in_region[static_cast<std::size_t>(r)] = in_region;
          if (share) {
            std::uint32_t own = 0;
            for (const auto& q : row) own += share->owns(q) ? 1u : 0u;
            row_owned[static_cast<std::size_t>(r)] = own;
          }
        } catch (...) {
#pragma omp critical(swell_fill_error)
          if (!error) error = std::current_exception();
        }
      }
    }
    if (error) std::rethrow_exception(error);

    std::size_t total = 0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      total += rows[r].size();
      fb.report.in_region += row_in_region[r];
    }
    fb.points.reserve(total);
    for (auto& row : rows) fb.points.insert(fb.points.end(), row.begin(), row.end());
    fb.report.particles = fb.points.size();
    if (share) {
      fb.row_points.resize(rows.size());
      for (std::size_t r = 0; r < rows.size(); ++r)
        fb.row_points[r] = static_cast<std::uint32_t>(rows[r].size());
      fb.row_owned = std::move(row_owned);
      fb.report.particles = 0;
      for (const auto n : fb.row_owned) fb.report.particles += n;
    }
    if (!b.fluid) fb.report.in_region = 0;
    if (fb.points.empty() && !share)
      throw std::invalid_argument("body '" + b.name +
                                  "' holds no particle at dp = " + std::to_string(dp) +
                                  " (is it thinner than dp, or inside a wall?)");
    if (b.fluid && bi + 1 < bodies.size()) {
      bool later_fluid = false;
      for (std::size_t e = bi + 1; e < bodies.size(); ++e) later_fluid |= bodies[e].fluid;
      if (later_fluid) {
        for (const auto& p : fb.points) {
          taken.insert(lattice_key(p, dp));
          taken_bounds.extend(p);
        }
      }
    }
    out.push_back(std::move(fb));
  }
  return out;
}

}  // namespace swell::geometry
