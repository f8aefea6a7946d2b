#include "geometry/primitives.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace swell::geometry {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fmt(const Eigen::Vector3d& v, int dim) {
  return format_point(v, dim);
}

void check_dim(int dim, const char* what) {
  if (dim != 2 && dim != 3) throw std::invalid_argument(std::string(what) + ": dim must be 2 or 3");
}

void check_radius(double r, const char* what) {
  if (!(r > 0.0) || !std::isfinite(r))
    throw std::invalid_argument(std::string(what) + ": radius must be positive");
}

Eigen::Vector2d segment_closest(const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                                const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a, aq = q - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp(aq.dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

// The nearest of the candidate surface points of a CSG result that lie on its surface
// (|signed distance| within a small tolerance of the candidate's size), else the nearest
// candidate.
Eigen::Vector3d nearest_on_surface(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& c,
                                   const Shape& result) {
  Eigen::Vector3d best = c.front(), best_any = c.front();
  double best2 = std::numeric_limits<double>::infinity(), any2 = best2;
  for (const auto& x : c) {
    const double e2 = (x - p).squaredNorm();
    if (e2 < any2) {
      any2 = e2;
      best_any = x;
    }
    const double tol = 1e-9 * (1.0 + x.cwiseAbs().maxCoeff());
    if (e2 < best2 && std::abs(result.signed_distance(x)) <= tol) {
      best2 = e2;
      best = x;
    }
  }
  return std::isfinite(best2) ? best : best_any;
}

// Even-odd crossing test of q against one closed loop.
bool inside_loop(const Eigen::Vector2d& q, const std::vector<Eigen::Vector2d>& loop) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Eigen::Vector2d &a = loop[i], &b = loop[j];
    if ((a.y() > q.y()) != (b.y() > q.y())) {
      const double x = a.x() + (q.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (x > q.x()) in = !in;
    }
  }
  return in;
}

double shoelace(const std::vector<Eigen::Vector2d>& loop) {
  double a = 0.0;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
    a += loop[j].x() * loop[i].y() - loop[i].x() * loop[j].y();
  return 0.5 * a;
}

}  // namespace

std::string format_point(const Eigen::Vector3d& v, int dim) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << v.x() << ", " << v.y();
  if (dim == 3) s << ", " << v.z();
  s << ")";
  return s.str();
}

bool overlaps(const Aabb& a, const Aabb& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

// ---------------------------------------------------------------------------------------------
// Box

BoxShape::BoxShape(const Eigen::Vector3d& min, const Eigen::Vector3d& max, int dim) : dim_(dim) {
  check_dim(dim, "box");
  box_.min = min;
  box_.max = max;
  if (dim == 2) box_.min.z() = box_.max.z() = 0.0;
  for (int d = 0; d < dim; ++d)
    if (!(min[d] < max[d])) throw std::invalid_argument("box: min must be below max on every axis");
}

double BoxShape::signed_distance(const Eigen::Vector3d& p) const {
  return box_.signed_distance(p, dim_);
}

Eigen::Vector3d BoxShape::closest_point_on_faces(const Eigen::Vector3d& p, unsigned open) const {
  // The nearest point of each face (a rectangle: p clamped to the box, pinned to the face's
  // plane), the nearest of those.
  Eigen::Vector3d clamped = p;
  for (int d = 0; d < dim_; ++d) clamped[d] = std::clamp(p[d], box_.min[d], box_.max[d]);
  if (dim_ == 2) clamped.z() = 0.0;
  Eigen::Vector3d best = clamped;
  double best2 = std::numeric_limits<double>::infinity();
  for (int d = 0; d < dim_; ++d)
    for (int side = 0; side < 2; ++side) {
      if (open & (1u << (2 * d + side))) continue;
      Eigen::Vector3d q = clamped;
      q[d] = side ? box_.max[d] : box_.min[d];
      const double e2 = (q - p).head(dim_).squaredNorm();
      if (e2 < best2) {
        best2 = e2;
        best = q;
      }
    }
  return best;
}

Eigen::Vector3d BoxShape::closest_surface_point(const Eigen::Vector3d& p) const {
  return closest_point_on_faces(p, 0u);
}

bool BoxShape::contains(const Eigen::Vector3d& p) const {
  return box_.contains(p, dim_);
}

Aabb BoxShape::bounds() const {
  return {box_.min, box_.max};
}

double BoxShape::volume() const {
  return box_.volume(dim_);
}

std::string BoxShape::describe() const {
  return "box " + fmt(box_.min, dim_) + "-" + fmt(box_.max, dim_);
}

// ---------------------------------------------------------------------------------------------
// Cylinder

CylinderShape::CylinderShape(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, double radius,
                             int dim)
    : p1_(p1), p2_(p2), radius_(radius), length_(0.0), dim_(dim) {
  check_dim(dim, "cylinder");
  check_radius(radius, "cylinder");
  if (dim == 2) {
    p1_.z() = 0.0;
    p2_ = p1_;
    axis_ = Eigen::Vector3d::UnitZ();
    return;
  }
  length_ = (p2 - p1).norm();
  if (!(length_ > 0.0)) throw std::invalid_argument("cylinder: p1 and p2 must differ");
  axis_ = (p2 - p1) / length_;
}

double CylinderShape::signed_distance(const Eigen::Vector3d& p) const {
  if (dim_ == 2) return (p.head<2>() - p1_.head<2>()).norm() - radius_;
  // In the (radial, axial) half-plane the cylinder is the rectangle [0, R] x [0, L]; the
  // distance to a rectangle centred at (0, L/2) with half sizes (R, L/2) (Quilez' capped
  // cylinder), exact inside and outside, rims included.
  const Eigen::Vector3d r = p - p1_;
  const double t = r.dot(axis_);
  const double rho = (r - t * axis_).norm();
  const double dx = rho - radius_;
  const double dy = std::abs(t - 0.5 * length_) - 0.5 * length_;
  const double out = std::hypot(std::max(dx, 0.0), std::max(dy, 0.0));
  return std::min(std::max(dx, dy), 0.0) + out;
}

Eigen::Vector3d CylinderShape::closest_surface_point(const Eigen::Vector3d& p) const {
  if (dim_ == 2) {
    const Eigen::Vector2d r = p.head<2>() - p1_.head<2>();
    const double n = r.norm();
    const Eigen::Vector2d u = n > 0.0 ? Eigen::Vector2d(r / n) : Eigen::Vector2d::UnitX();
    const Eigen::Vector2d q = p1_.head<2>() + radius_ * u;
    return {q.x(), q.y(), 0.0};
  }
  // Candidates: the side (radial projection, axial position clamped) and the two caps (the
  // point projected on the cap's plane, radius clamped to R); the nearest wins.
  const Eigen::Vector3d r = p - p1_;
  const double t = r.dot(axis_);
  const Eigen::Vector3d radial = r - t * axis_;
  const double rho = radial.norm();
  Eigen::Vector3d u = rho > 0.0 ? Eigen::Vector3d(radial / rho) : axis_.unitOrthogonal();
  const Eigen::Vector3d side = p1_ + std::clamp(t, 0.0, length_) * axis_ + radius_ * u;
  const double rc = std::min(rho, radius_);
  const Eigen::Vector3d cap1 = p1_ + rc * u, cap2 = p1_ + length_ * axis_ + rc * u;
  Eigen::Vector3d best = side;
  for (const Eigen::Vector3d& c : {cap1, cap2})
    if ((c - p).squaredNorm() < (best - p).squaredNorm()) best = c;
  return best;
}

Aabb CylinderShape::bounds() const {
  if (dim_ == 2) {
    const Eigen::Vector3d e(radius_, radius_, 0.0);
    return {p1_ - e, p1_ + e};
  }
  // A disc of radius R with unit normal u extends R sqrt(1 - u_i^2) along axis i.
  const Eigen::Vector3d e =
      radius_ * (Eigen::Vector3d::Ones() - axis_.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
  return {p1_.cwiseMin(p2_) - e, p1_.cwiseMax(p2_) + e};
}

double CylinderShape::volume() const {
  const double disc = std::numbers::pi * radius_ * radius_;
  return dim_ == 2 ? disc : disc * length_;
}

std::string CylinderShape::describe() const {
  std::ostringstream s;
  s.precision(6);
  if (dim_ == 2)
    s << "disc centre " << fmt(p1_, 2) << " r " << radius_;
  else
    s << "cylinder " << fmt(p1_, 3) << "-" << fmt(p2_, 3) << " r " << radius_;
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Sphere

SphereShape::SphereShape(const Eigen::Vector3d& center, double radius, int dim)
    : center_(center), radius_(radius), dim_(dim) {
  check_dim(dim, "sphere");
  check_radius(radius, "sphere");
  if (dim == 2) center_.z() = 0.0;
}

double SphereShape::signed_distance(const Eigen::Vector3d& p) const {
  if (dim_ == 2) return (p.head<2>() - center_.head<2>()).norm() - radius_;
  return (p - center_).norm() - radius_;
}

Eigen::Vector3d SphereShape::closest_surface_point(const Eigen::Vector3d& p) const {
  Eigen::Vector3d r = p - center_;
  if (dim_ == 2) r.z() = 0.0;
  const double n = r.norm();
  const Eigen::Vector3d u = n > 0.0 ? Eigen::Vector3d(r / n) : Eigen::Vector3d::UnitX();
  return center_ + radius_ * u;
}

Aabb SphereShape::bounds() const {
  Eigen::Vector3d e = Eigen::Vector3d::Constant(radius_);
  if (dim_ == 2) e.z() = 0.0;
  return {center_ - e, center_ + e};
}

double SphereShape::volume() const {
  const double r = radius_;
  return dim_ == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

std::string SphereShape::describe() const {
  std::ostringstream s;
  s.precision(6);
  s << (dim_ == 2 ? "disc" : "sphere") << " centre " << fmt(center_, dim_) << " r " << radius_;
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Polygon

PolygonShape::PolygonShape(std::vector<std::vector<Eigen::Vector2d>> loops, std::string description)
    : loops_(std::move(loops)), description_(std::move(description)) {
  for (auto& loop : loops_) {
    if (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();  // explicitly closed
    if (loop.size() < 3)
      throw std::invalid_argument(description_ + ": every loop needs at least 3 points");
  }
  if (loops_.empty()) throw std::invalid_argument(description_ + ": no loop");
  lo_ = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  hi_ = -lo_;
  for (const auto& loop : loops_)
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
      if (!loop[i].allFinite())
        throw std::invalid_argument(description_ + ": non-finite coordinate");
      edges_.push_back({loop[j], loop[i]});
      lo_ = lo_.cwiseMin(loop[i]);
      hi_ = hi_.cwiseMax(loop[i]);
    }
  const Eigen::Vector2d ext = hi_ - lo_;
  if (!(ext.x() > 0.0) || !(ext.y() > 0.0))
    throw std::invalid_argument(description_ + ": the points enclose no area");

  // Even-odd area of non-crossing loops: a loop inside an odd number of others is a hole.
  for (std::size_t i = 0; i < loops_.size(); ++i) {
    int depth = 0;
    for (std::size_t j = 0; j < loops_.size(); ++j)
      if (j != i && inside_loop(loops_[i][0], loops_[j])) ++depth;
    area_ += (depth % 2 == 0 ? 1.0 : -1.0) * std::abs(shoelace(loops_[i]));
  }

  // About one edge per cell, at most 1024 cells per axis.
  const double n = static_cast<double>(edges_.size());
  cell_ = std::max(std::sqrt(ext.x() * ext.y() / n), std::max(ext.x(), ext.y()) / 1024.0);
  nx_ = std::max(1, static_cast<int>(std::ceil(ext.x() / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil(ext.y() / cell_)));
  auto cell_of = [&](double v, double o, int n) {
    return std::clamp(static_cast<int>(std::floor((v - o) / cell_)), 0, n - 1);
  };
  // Counting pass, then fill (CSR).
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
      cell_edges_.resize(static_cast<std::size_t>(cell_start_.back()));
      fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    }
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      const Eigen::Vector2d a = edges_[e].a.cwiseMin(edges_[e].b);
      const Eigen::Vector2d b = edges_[e].a.cwiseMax(edges_[e].b);
      for (int iy = cell_of(a.y(), lo_.y(), ny_); iy <= cell_of(b.y(), lo_.y(), ny_); ++iy)
        for (int ix = cell_of(a.x(), lo_.x(), nx_); ix <= cell_of(b.x(), lo_.x(), nx_); ++ix) {
          const std::size_t c = static_cast<std::size_t>(iy) * nx_ + ix;
          if (pass == 0)
            ++cell_start_[c + 1];
          else
            cell_edges_[static_cast<std::size_t>(fill[c]++)] = static_cast<int>(e);
        }
    }
  }

  nslab_ = ny_;
  slab_ = ext.y() / nslab_;
  auto slab_of = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - lo_.y()) / slab_)), 0, nslab_ - 1);
  };
  slab_start_.assign(static_cast<std::size_t>(nslab_) + 1, 0);
  for (const auto& e : edges_)
    for (int s = slab_of(std::min(e.a.y(), e.b.y())); s <= slab_of(std::max(e.a.y(), e.b.y())); ++s)
      ++slab_start_[static_cast<std::size_t>(s) + 1];
  for (std::size_t s = 1; s < slab_start_.size(); ++s) slab_start_[s] += slab_start_[s - 1];
  slab_edges_.resize(static_cast<std::size_t>(slab_start_.back()));
  std::vector<int> fill(slab_start_.begin(), slab_start_.end() - 1);
  for (std::size_t e = 0; e < edges_.size(); ++e) {
    const Edge& E = edges_[e];
    for (int s = slab_of(std::min(E.a.y(), E.b.y())); s <= slab_of(std::max(E.a.y(), E.b.y())); ++s)
      slab_edges_[static_cast<std::size_t>(fill[static_cast<std::size_t>(s)]++)] =
          static_cast<int>(e);
  }
}

bool PolygonShape::inside(const Eigen::Vector2d& q) const {
  if (q.x() < lo_.x() || q.x() > hi_.x() || q.y() < lo_.y() || q.y() > hi_.y()) return false;
  const int s = std::clamp(static_cast<int>(std::floor((q.y() - lo_.y()) / slab_)), 0, nslab_ - 1);
  bool in = false;
  for (int k = slab_start_[s]; k < slab_start_[s + 1]; ++k) {
    const Edge& e = edges_[static_cast<std::size_t>(slab_edges_[static_cast<std::size_t>(k)])];
    if ((e.a.y() > q.y()) != (e.b.y() > q.y())) {
      const double x = e.a.x() + (q.y() - e.a.y()) / (e.b.y() - e.a.y()) * (e.b.x() - e.a.x());
      if (x > q.x()) in = !in;
    }
  }
  return in;
}

double PolygonShape::unsigned_distance(const Eigen::Vector2d& q) const {
  return (nearest_edge_point(q) - q).norm();
}

Eigen::Vector2d PolygonShape::nearest_edge_point(const Eigen::Vector2d& q) const {
  const int cx = std::clamp(static_cast<int>(std::floor((q.x() - lo_.x()) / cell_)), 0, nx_ - 1);
  const int cy = std::clamp(static_cast<int>(std::floor((q.y() - lo_.y()) / cell_)), 0, ny_ - 1);
  double best2 = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best = q;
  auto visit = [&](int ix, int iy) {
    if (ix < 0 || ix >= nx_ || iy < 0 || iy >= ny_) return;
    const std::size_t c = static_cast<std::size_t>(iy) * nx_ + ix;
    for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const Edge& e = edges_[static_cast<std::size_t>(cell_edges_[static_cast<std::size_t>(k)])];
      const Eigen::Vector2d x = segment_closest(q, e.a, e.b);
      const double e2 = (x - q).squaredNorm();
      if (e2 < best2) {
        best2 = e2;
        best = x;
      }
    }
  };
  // Rings of cells around q's (clamped) cell. A cell of ring k + 1 lies at least k cells
  // away from q, so once the best distance is within k * cell_ no farther edge can win.
  const int kmax = std::max({cx, nx_ - 1 - cx, cy, ny_ - 1 - cy});
  for (int k = 0; k <= kmax; ++k) {
    for (int iy = cy - k; iy <= cy + k; ++iy) {
      if (iy == cy - k || iy == cy + k) {
        for (int ix = cx - k; ix <= cx + k; ++ix) visit(ix, iy);
      } else {
        visit(cx - k, iy);
        visit(cx + k, iy);
      }
    }
    if (best2 <= (k * cell_) * (k * cell_)) break;
  }
  return best;
}

Eigen::Vector3d PolygonShape::closest_surface_point(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d x = nearest_edge_point(p.head<2>());
  return {x.x(), x.y(), 0.0};
}

double PolygonShape::signed_distance(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d q = p.head<2>();
  const double d = unsigned_distance(q);
  return inside(q) ? -d : d;
}

bool PolygonShape::contains(const Eigen::Vector3d& p) const {
  return inside(p.head<2>());
}

Aabb PolygonShape::bounds() const {
  return {Eigen::Vector3d(lo_.x(), lo_.y(), 0.0), Eigen::Vector3d(hi_.x(), hi_.y(), 0.0)};
}

double PolygonShape::volume() const {
  return area_;
}

std::string PolygonShape::describe() const {
  std::ostringstream s;
  s << description_ << " (" << loops_.size() << (loops_.size() == 1 ? " loop, " : " loops, ")
    << edges_.size() << " edges)";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// CSG

UnionShape::UnionShape(std::vector<ShapePtr> children) : children_(std::move(children)) {
  if (children_.empty()) throw std::invalid_argument("union: needs at least one shape");
  for (const auto& c : children_) bounds_.extend(c->bounds());
}

double UnionShape::signed_distance(const Eigen::Vector3d& p) const {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& c : children_) d = std::min(d, c->signed_distance(p));
  return d;
}

Eigen::Vector3d UnionShape::closest_surface_point(const Eigen::Vector3d& p) const {
  std::vector<Eigen::Vector3d> c;
  c.reserve(children_.size());
  for (const auto& ch : children_) c.push_back(ch->closest_surface_point(p));
  return nearest_on_surface(p, c, *this);
}

bool UnionShape::contains(const Eigen::Vector3d& p) const {
  for (const auto& c : children_) {
    const Aabb b = c->bounds();
    if ((p.array() < b.min.array()).any() || (p.array() > b.max.array()).any()) continue;
    if (c->contains(p)) return true;
  }
  return false;
}

double UnionShape::volume() const {
  double v = 0.0;
  for (std::size_t i = 0; i < children_.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (overlaps(children_[i]->bounds(), children_[j]->bounds())) return kNaN;
    v += children_[i]->volume();
  }
  return v;
}

std::string UnionShape::describe() const {
  std::string s = "union of";
  for (std::size_t i = 0; i < children_.size(); ++i)
    s += (i ? ", " : " ") + children_[i]->describe();
  return s;
}

DifferenceShape::DifferenceShape(ShapePtr base, std::vector<ShapePtr> cut)
    : base_(std::move(base)), cut_(std::move(cut)) {
  if (!base_ || cut_.empty())
    throw std::invalid_argument("difference: needs a shape and at least one shape to remove");
}

double DifferenceShape::signed_distance(const Eigen::Vector3d& p) const {
  double d = base_->signed_distance(p);
  for (const auto& c : cut_) d = std::max(d, -c->signed_distance(p));
  return d;
}

Eigen::Vector3d DifferenceShape::closest_surface_point(const Eigen::Vector3d& p) const {
  std::vector<Eigen::Vector3d> c;
  c.reserve(cut_.size() + 1);
  c.push_back(base_->closest_surface_point(p));
  for (const auto& ch : cut_) c.push_back(ch->closest_surface_point(p));
  return nearest_on_surface(p, c, *this);
}

bool DifferenceShape::contains(const Eigen::Vector3d& p) const {
  if (!base_->contains(p)) return false;
  for (const auto& c : cut_) {
    const Aabb b = c->bounds();
    if ((p.array() < b.min.array()).any() || (p.array() > b.max.array()).any()) continue;
    if (c->contains(p)) return false;
  }
  return true;
}

double DifferenceShape::volume() const {
  // Known in two cases: no cut meets the base's bounds, or the base is a box (it fills its
  // bounds) and the cuts lie within them without overlapping each other.
  const Aabb bb = base_->bounds();
  bool apart = true, within = dynamic_cast<const BoxShape*>(base_.get()) != nullptr;
  double removed = 0.0;
  for (std::size_t i = 0; i < cut_.size(); ++i) {
    const Aabb c = cut_[i]->bounds();
    apart = apart && !overlaps(bb, c);
    within = within && (c.min.array() >= bb.min.array()).all() &&
             (c.max.array() <= bb.max.array()).all();
    for (std::size_t j = 0; j < i; ++j) within = within && !overlaps(c, cut_[j]->bounds());
    removed += cut_[i]->volume();
  }
  if (apart) return base_->volume();
  if (within) return base_->volume() - removed;
  return kNaN;
}

std::string DifferenceShape::describe() const {
  std::string s = base_->describe() + " minus";
  for (std::size_t i = 0; i < cut_.size(); ++i) s += (i ? ", " : " ") + cut_[i]->describe();
  return s;
}

}  // namespace swell::geometry
