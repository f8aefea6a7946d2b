// Shapes and the lattice fill: each primitive's signed distance against an independent
// analytic formula and its volume; polygon grid queries against brute force; particle counts
// against exact volumes (aligned boxes: exact; curved shapes: within half a lattice cell over
// the surface, |N dp^D - V| <= A dp / 2); no two particles of different bodies closer than dp;
// fill_below; union and difference; identical particles for 1 and 2 threads and with marching
// on and off; meshes (box and sphere STL written here) and a timed ~1M-particle mesh fill.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>
#include <vtkAbstractArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <unordered_map>

#include "apps/fill_command.hpp"
#include "case/reader.hpp"
#include "geometry/lattice_fill.hpp"
#include "geometry/primitives.hpp"
#include "geometry/shape_factory.hpp"
#include "run/run.hpp"

namespace swell::geometry {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

std::mt19937 rng(12345);
Vector3d random_point(const Vector3d& lo, const Vector3d& hi, int dim) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Vector3d p;
  for (int d = 0; d < 3; ++d) p[d] = lo[d] + u(rng) * (hi[d] - lo[d]);
  if (dim == 2) p.z() = 0.0;
  return p;
}

// ------------------------------------------------------------------------------- primitives

TEST(Primitives, BoxMaxNormDistanceAndVolume) {
  const BoxShape b3(Vector3d(0, 0, 0), Vector3d(2, 1, 1), 3);
  EXPECT_DOUBLE_EQ(b3.signed_distance(Vector3d(1, 0.5, 0.5)), -0.5);
  EXPECT_DOUBLE_EQ(b3.signed_distance(Vector3d(1, 0.5, 0.9)), -0.1);
  EXPECT_DOUBLE_EQ(b3.signed_distance(Vector3d(3, 0.5, 0.5)), 1.0);
  EXPECT_DOUBLE_EQ(b3.signed_distance(Vector3d(3, 2, 0.5)), 1.0);  // corner: max-norm
  EXPECT_DOUBLE_EQ(b3.signed_distance(Vector3d(-0.5, -2, 3)), 2.0);
  EXPECT_DOUBLE_EQ(b3.volume(), 2.0);
  const BoxShape b2(Vector3d(0, 0, 5), Vector3d(2, 1, 7), 2);  // z ignored
  EXPECT_DOUBLE_EQ(b2.signed_distance(Vector3d(1, 0.25, 100)), -0.25);
  EXPECT_DOUBLE_EQ(b2.volume(), 2.0);
  EXPECT_EQ(b2.bounds().min.z(), 0.0);
  EXPECT_THROW(BoxShape(Vector3d(0, 0, 0), Vector3d(1, 0, 1), 3), std::invalid_argument);
}

TEST(Primitives, SphereDistanceAndVolume) {
  const Vector3d c(0.3, -0.2, 0.5);
  const SphereShape s3(c, 0.7, 3), s2(c, 0.7, 2);
  for (int n = 0; n < 200; ++n) {
    const Vector3d p = random_point(Vector3d::Constant(-2), Vector3d::Constant(2), 3);
    EXPECT_NEAR(s3.signed_distance(p), (p - c).norm() - 0.7, 1e-14);
    EXPECT_NEAR(s2.signed_distance(p), std::hypot(p.x() - c.x(), p.y() - c.y()) - 0.7, 1e-14);
  }
  EXPECT_DOUBLE_EQ(s3.volume(), 4.0 / 3.0 * kPi * 0.343);
  EXPECT_DOUBLE_EQ(s2.volume(), kPi * 0.49);
}

// Capped cylinder distance by cases in the (radial rho, axial t) half plane.
double cylinder_reference(double rho, double t, double r, double len) {
  const bool radial_in = rho <= r, axial_in = t >= 0 && t <= len;
  if (radial_in && axial_in) return -std::min({r - rho, t, len - t});
  if (axial_in) return rho - r;            // beside the mantle
  const double dt = t < 0 ? -t : t - len;  // beyond a cap
  if (radial_in) return dt;                // facing the cap
  return std::hypot(rho - r, dt);          // nearest the rim
}

TEST(Primitives, CylinderExactDistanceCapsAndRims) {
  const Vector3d p1(0.1, 0.2, -0.3), p2(1.1, 0.7, 0.4);
  const double r = 0.25, len = (p2 - p1).norm();
  const Vector3d u = (p2 - p1) / len;
  const CylinderShape cyl(p1, p2, r, 3);
  for (int n = 0; n < 2000; ++n) {
    const Vector3d p = random_point(Vector3d(-1, -1, -1.5), Vector3d(2, 2, 1.5), 3);
    const double t = (p - p1).dot(u), rho = (p - p1 - t * u).norm();
    EXPECT_NEAR(cyl.signed_distance(p), cylinder_reference(rho, t, r, len), 1e-12) << p.transpose();
  }
  EXPECT_NEAR(cyl.volume(), kPi * r * r * len, 1e-14);
  // Bounds hold the caps' rims: sample the rims.
  const Aabb b = cyl.bounds();
  Vector3d e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  for (int k = 0; k < 64; ++k) {
    const double a = 2 * kPi * k / 64;
    for (const Vector3d& c : {p1, p2}) {
      const Vector3d q = c + r * (std::cos(a) * e1 + std::sin(a) * e2);
      EXPECT_TRUE((q.array() >= b.min.array() - 1e-12).all() &&
                  (q.array() <= b.max.array() + 1e-12).all());
    }
  }
  const CylinderShape disc(Vector3d(1, 2, 9), Vector3d(5, 5, 5), 0.5, 2);  // 2D: disc at p1
  EXPECT_NEAR(disc.signed_distance(Vector3d(1, 3, 0)), 0.5, 1e-14);
  EXPECT_NEAR(disc.volume(), kPi * 0.25, 1e-14);
}

double segment_distance(const Vector2d& q, const Vector2d& a, const Vector2d& b) {
  const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (q - a - t * (b - a)).norm();
}

TEST(Primitives, PolygonWithHoleDistanceSignAndArea) {
  // A 4 x 3 square with a 1 x 1 square hole (both loops counter-clockwise: even-odd rule).
  const std::vector<Vector2d> outer = {{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  const std::vector<Vector2d> hole = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  const PolygonShape poly({outer, hole});
  EXPECT_DOUBLE_EQ(poly.volume(), 12.0 - 1.0);
  for (int n = 0; n < 2000; ++n) {
    const Vector3d p = random_point(Vector3d(-1, -1, 0), Vector3d(5, 4, 0), 2);
    const Vector2d q = p.head<2>();
    double d = 1e300;
    for (const auto* loop : {&outer, &hole})
      for (std::size_t i = 0; i < loop->size(); ++i)
        d = std::min(d, segment_distance(q, (*loop)[i], (*loop)[(i + 1) % loop->size()]));
    const bool in_outer = q.x() > 0 && q.x() < 4 && q.y() > 0 && q.y() < 3;
    const bool in_hole = q.x() > 1 && q.x() < 2 && q.y() > 1 && q.y() < 2;
    EXPECT_NEAR(poly.signed_distance(p), in_outer && !in_hole ? -d : d, 1e-12) << q.transpose();
  }
  // A triangle, given clockwise: shoelace area regardless of orientation.
  const PolygonShape tri({{{0, 0}, {0, 2}, {3, 0}}});
  EXPECT_DOUBLE_EQ(tri.volume(), 3.0);
}

TEST(Primitives, PolygonGridQueriesMatchBruteForce) {
  // A wavy closed curve of 5000 edges: the binned queries must equal the brute-force ones.
  std::vector<Vector2d> loop;
  const int n = 5000;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n, r = 1.0 + 0.3 * std::sin(7 * a);
    loop.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  const PolygonShape poly({loop});
  for (int k = 0; k < 3000; ++k) {
    const Vector3d p = random_point(Vector3d(-3, -3, 0), Vector3d(3, 3, 0), 2);
    double d = 1e300;
    for (int i = 0; i < n; ++i)
      d = std::min(d, segment_distance(p.head<2>(), loop[i], loop[(i + 1) % n]));
    // Inside by the curve's polar equation, independent of the polygon's crossing test.
    const double a = std::atan2(p.y(), p.x()), r = 1.0 + 0.3 * std::sin(7 * a);
    const bool in = p.head<2>().norm() < r;
    const double sd = poly.signed_distance(p);
    EXPECT_NEAR(std::abs(sd), d, 1e-12);
    if (d > 1e-3) {  // the polar test is approximate right at the edges
      EXPECT_EQ(sd < 0, in) << p.transpose();
    }
  }
}

TEST(Primitives, UnionAndDifference) {
  const auto a = std::make_shared<BoxShape>(Vector3d(0, 0, 0), Vector3d(1, 1, 1), 3);
  const auto b = std::make_shared<SphereShape>(Vector3d(1, 0.5, 0.5), 0.3, 3);
  const auto far = std::make_shared<SphereShape>(Vector3d(5, 5, 5), 0.5, 3);
  const UnionShape u({a, b});
  const DifferenceShape diff(a, {b});
  for (int n = 0; n < 500; ++n) {
    const Vector3d p = random_point(Vector3d::Constant(-0.5), Vector3d::Constant(1.5), 3);
    const double da = a->signed_distance(p), db = b->signed_distance(p);
    EXPECT_DOUBLE_EQ(u.signed_distance(p), std::min(da, db));
    EXPECT_DOUBLE_EQ(diff.signed_distance(p), std::max(da, -db));
    EXPECT_EQ(u.contains(p), da < 0 || db < 0);
    EXPECT_EQ(diff.contains(p), da < 0 && !(db < 0));
  }
  EXPECT_TRUE(std::isnan(u.volume()));  // overlapping children
  EXPECT_NEAR(UnionShape({a, far}).volume(), 1.0 + 4.0 / 3.0 * kPi * 0.125, 1e-14);
  EXPECT_TRUE(std::isnan(diff.volume()));  // the sphere pokes out of the box
  const auto inner = std::make_shared<SphereShape>(Vector3d(0.5, 0.5, 0.5), 0.3, 3);
  EXPECT_NEAR(DifferenceShape(a, {inner}).volume(), 1.0 - 4.0 / 3.0 * kPi * 0.027, 1e-14);
  EXPECT_DOUBLE_EQ(DifferenceShape(a, {far}).volume(), 1.0);
}

// --------------------------------------------------------------------------------- the fill

BodyGeometry fluid(const std::string& name, ShapePtr s) {
  BodyGeometry b;
  b.name = name;
  b.shape = std::move(s);
  return b;
}
BodyGeometry wall(const std::string& name, ShapePtr s, bool inside, int layers,
                  std::vector<std::string> open = {}) {
  BodyGeometry b;
  b.name = name;
  b.fluid = false;
  b.shape = std::move(s);
  b.walls_inside = inside;
  b.layers = layers;
  b.open = std::move(open);
  return b;
}
ShapePtr box(Vector3d lo, Vector3d hi, int dim) {
  return std::make_shared<BoxShape>(lo, hi, dim);
}

std::vector<FilledBody> fill(const std::vector<BodyGeometry>& bodies, int dim, double dp,
                             bool march = true) {
  FillOptions o;
  o.dim = dim;
  o.dp = dp;
  o.march = march;
  return fill_bodies(bodies, o);
}

// Smallest distance between points of different bodies (grid of cells dp wide).
double min_distance_across_bodies(const std::vector<FilledBody>& bodies, double dp) {
  std::unordered_map<std::uint64_t, std::vector<std::pair<int, Vector3d>>> cells;
  auto key = [&](long i, long j, long k) {
    return (static_cast<std::uint64_t>(i + (1 << 20)) << 42) |
           (static_cast<std::uint64_t>(j + (1 << 20)) << 21) |
           static_cast<std::uint64_t>(k + (1 << 20));
  };
  auto cell = [&](const Vector3d& p, int d) { return static_cast<long>(std::floor(p[d] / dp)); };
  for (std::size_t b = 0; b < bodies.size(); ++b)
    for (const auto& p : bodies[b].points)
      cells[key(cell(p, 0), cell(p, 1), cell(p, 2))].emplace_back(static_cast<int>(b), p);
  double best = 1e300;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    for (const auto& p : bodies[b].points)
      for (long di = -1; di <= 1; ++di)
        for (long dj = -1; dj <= 1; ++dj)
          for (long dk = -1; dk <= 1; ++dk) {
            const auto it = cells.find(key(cell(p, 0) + di, cell(p, 1) + dj, cell(p, 2) + dk));
            if (it == cells.end()) continue;
            for (const auto& [ob, q] : it->second)
              if (ob != static_cast<int>(b)) best = std::min(best, (p - q).norm());
          }
  return best;
}

TEST(LatticeFill, AlignedBoxHoldsItsVolumeExactly) {
  const double dp = 0.01;
  for (int dim : {2, 3}) {
    const auto f =
        fill({fluid("water", box(Vector3d(0.2, -0.1, 0), Vector3d(0.5, 0.3, 0.2), dim))}, dim, dp);
    const std::size_t expected = dim == 2 ? 30 * 40 : 30 * 40 * 20;
    EXPECT_EQ(f[0].points.size(), expected);
    EXPECT_NEAR(f[0].report.volume_error(dim, dp), 0.0, 1e-12);
  }
}

TEST(LatticeFill, SphereCountWithinSurfaceLayerOfVolume) {
  // Bound used: |N dp^D - V| <= A dp / 2 (half a lattice cell over the surface A).
  const double dp = 0.02, r = 0.37;
  for (int dim : {2, 3}) {
    const auto s = std::make_shared<SphereShape>(Vector3d(0.013, -0.021, 0.007), r, dim);
    const auto f = fill({fluid("ball", s)}, dim, dp);
    const double v = s->volume(), area = dim == 2 ? 2 * kPi * r : 4 * kPi * r * r;
    const double n_vol = f[0].points.size() * std::pow(dp, dim);
    EXPECT_LE(std::abs(n_vol - v), 0.5 * area * dp) << dim << "D";
    EXPECT_EQ(f[0].report.in_region, f[0].points.size());
    std::cout << "  " << dim << "D sphere r/dp = " << r / dp
              << ": N dp^D / V - 1 = " << f[0].report.volume_error(dim, dp) << " (bound "
              << 0.5 * area * dp / v << ")\n";
  }
}

// A tank with a box and a cylinder obstacle and a fluid block overlapping both.
std::vector<BodyGeometry> tank_case(int dim) {
  std::vector<BodyGeometry> b;
  b.push_back(wall("tank", box(Vector3d(0, 0, 0), Vector3d(1.0, 0.6, 0.5), dim), true, 3,
                   {dim == 2 ? "ymax" : "zmax"}));
  b.push_back(wall("block", box(Vector3d(0.6, 0, 0), Vector3d(0.7, 0.1, 0.2), dim), false, 2));
  b.push_back(wall(
      "pile",
      std::make_shared<CylinderShape>(Vector3d(0.3, 0.2, 0.0), Vector3d(0.3, 0.2, 0.5), 0.083, dim),
      false, 2));
  b.push_back(
      fluid("water", box(Vector3d(0, 0, 0), Vector3d(0.8, dim == 2 ? 0.4 : 0.6, 0.4), dim)));
  return b;
}

TEST(LatticeFill, BodiesNeverOverlap) {
  const double dp = 0.01;
  for (int dim : {2, 3}) {
    const auto f = fill(tank_case(dim), dim, dp);
    ASSERT_EQ(f.size(), 4u);
    for (const auto& b : f) EXPECT_GT(b.points.size(), 0u) << b.report.name;
    EXPECT_GE(min_distance_across_bodies(f, dp), 0.99 * dp) << dim << "D";
    // The obstacles took fluid points (inside them or within dp/2 of their surface).
    EXPECT_GT(f[3].report.in_region, f[3].points.size());
  }
}

TEST(LatticeFill, FillBelowInsideBoxTank) {
  const double dp = 0.01;
  for (int dim : {2, 3}) {
    for (double level : {0.3, 0.305}) {
      std::vector<BodyGeometry> b;
      b.push_back(wall("tank", box(Vector3d(0, 0, 0), Vector3d(1.0, 0.5, 0.6), dim), true, 2));
      BodyGeometry w;
      w.name = "water";
      w.fill_below = level;
      w.container = 0;
      b.push_back(w);
      const auto f = fill(b, dim, dp);
      // Layers below the level: (j + 1/2) dp < level.
      const long layers = static_cast<long>(std::ceil(level / dp - 0.5));
      const std::size_t expected = dim == 2 ? 100 * layers : 100 * 50 * layers;
      EXPECT_EQ(f[1].points.size(), expected) << dim << "D level " << level;
      const double v = level * (dim == 2 ? 1.0 : 0.5);
      EXPECT_NEAR(f[1].report.region_volume, v, 1e-12);
      // With an aligned block on the floor: exactly its cells are removed.
      b.insert(b.begin() + 1,
               wall("block", box(Vector3d(0.4, 0, 0), Vector3d(0.6, 0.1, 0.2), dim), false, 2));
      const auto g = fill(b, dim, dp);
      EXPECT_EQ(g[2].points.size(), expected - (dim == 2 ? 20 * 10 : 20 * 10 * 20));
      EXPECT_GE(min_distance_across_bodies(g, dp), 0.99 * dp);
    }
  }
  std::vector<BodyGeometry> bad = {fluid("f", box(Vector3d(0, 0, 0), Vector3d(1, 1, 1), 2))};
  bad[0].shape = nullptr;
  bad[0].fill_below = 0.5;
  bad[0].container = 0;  // itself: not a boundary body
  EXPECT_THROW(fill(bad, 2, 0.1), std::invalid_argument);
}

TEST(LatticeFill, UnionAndDifferenceCounts) {
  const double dp = 0.01;
  const int dim = 2;
  const auto a = box(Vector3d(0, 0, 0), Vector3d(0.5, 0.3, 0), dim);
  const auto b = box(Vector3d(0.3, 0.2, 0), Vector3d(0.6, 0.5, 0), dim);
  const auto u =
      fill({fluid("u", std::make_shared<UnionShape>(std::vector<ShapePtr>{a, b}))}, dim, dp);
  EXPECT_EQ(u[0].points.size(), 50u * 30 + 30 * 30 - 20 * 10);
  const auto d =
      fill({fluid("d", std::make_shared<DifferenceShape>(a, std::vector<ShapePtr>{b}))}, dim, dp);
  EXPECT_EQ(d[0].points.size(), 50u * 30 - 20 * 10);
  // 3D box minus a ball inside it: V known exactly, count within the surface-layer bound.
  const auto cube = box(Vector3d(0, 0, 0), Vector3d(0.4, 0.4, 0.4), 3);
  const auto ball = std::make_shared<SphereShape>(Vector3d(0.2, 0.21, 0.19), 0.12, 3);
  const auto hollow = std::make_shared<DifferenceShape>(cube, std::vector<ShapePtr>{ball});
  const auto h = fill({fluid("h", hollow)}, 3, dp);
  EXPECT_LE(std::abs(h[0].points.size() * std::pow(dp, 3) - hollow->volume()),
            0.5 * 4 * kPi * 0.12 * 0.12 * dp);
}

TEST(LatticeFill, PolygonAreaAndCount) {
  const double dp = 0.01;
  // Aligned L-shape: exact count; a triangle: within the boundary-layer bound.
  const auto l = std::make_shared<PolygonShape>(std::vector<std::vector<Vector2d>>{
      {{0, 0}, {0.4, 0}, {0.4, 0.1}, {0.1, 0.1}, {0.1, 0.3}, {0, 0.3}}});
  EXPECT_NEAR(l->volume(), 0.04 + 0.02, 1e-15);
  EXPECT_EQ(fill({fluid("l", l)}, 2, dp)[0].points.size(), 40u * 10 + 10 * 20);
  const auto tri = std::make_shared<PolygonShape>(
      std::vector<std::vector<Vector2d>>{{{0.013, 0.0}, {0.5, 0.07}, {0.2, 0.41}}});
  const auto f = fill({fluid("t", tri)}, 2, dp);
  const double perimeter = (Vector2d(0.5, 0.07) - Vector2d(0.013, 0)).norm() +
                           (Vector2d(0.2, 0.41) - Vector2d(0.5, 0.07)).norm() +
                           (Vector2d(0.013, 0) - Vector2d(0.2, 0.41)).norm();
  EXPECT_LE(std::abs(f[0].points.size() * dp * dp - tri->volume()), 0.5 * perimeter * dp);
}

// A mixed case exercising every path: tank, obstacles, two fluid bodies (one below a level).
std::vector<BodyGeometry> mixed_case(int dim) {
  auto b = tank_case(dim);
  b.push_back(fluid("drop", std::make_shared<SphereShape>(Vector3d(0.5, 0.45, 0.3), 0.12, dim)));
  BodyGeometry w;
  w.name = "pool";
  w.fill_below = 0.2;
  w.container = 0;
  b.push_back(w);
  return b;
}

TEST(LatticeFill, SameParticlesForAnyThreadCountAndWithoutMarching) {
  const double dp = 0.01;
  for (int dim : {2, 3}) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const auto one = fill(mixed_case(dim), dim, dp);
    omp_set_num_threads(2);
    const auto two = fill(mixed_case(dim), dim, dp);
    const auto direct = fill(mixed_case(dim), dim, dp, false);
    omp_set_num_threads(saved);
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t b = 0; b < one.size(); ++b) {
      EXPECT_EQ(one[b].points, two[b].points) << one[b].report.name;
      EXPECT_EQ(one[b].points, direct[b].points) << one[b].report.name;
    }
    EXPECT_GE(min_distance_across_bodies(one, dp), 0.99 * dp);
  }
}

// ------------------------------------------------------------------------------------ meshes

const std::filesystem::path& temp_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("swell_test_geometry_fill_" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}
class TempDirCleanup : public ::testing::Environment {
 public:
  void TearDown() override { std::filesystem::remove_all(temp_dir()); }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new TempDirCleanup);

using Tri = std::array<Vector3d, 3>;
void write_binary_stl(const std::string& path, const std::vector<Tri>& tris) {
  std::ofstream f(path, std::ios::binary);
  const char header[80] = "swell test mesh";
  f.write(header, 80);
  const auto n = static_cast<std::uint32_t>(tris.size());
  f.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : tris) {
    const Vector3d nrm = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    float v[12];
    for (int i = 0; i < 3; ++i) v[i] = static_cast<float>(nrm[i]);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) v[3 + 3 * k + i] = static_cast<float>(t[k][i]);
    f.write(reinterpret_cast<const char*>(v), sizeof v);
    const std::uint16_t attr = 0;
    f.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

std::vector<Tri> box_tris(const Vector3d& lo, const Vector3d& hi) {
  std::vector<Tri> t;
  auto corner = [&](int i) {
    return Vector3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  };
  // Each face as two triangles, outward: (a, b, c, d) counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    t.push_back({corner(f[0]), corner(f[1]), corner(f[2])});
    t.push_back({corner(f[0]), corner(f[2]), corner(f[3])});
  }
  return t;
}

// UV sphere with about 2 n^2 faces; vertices computed once, so shared corners are identical.
std::vector<Tri> sphere_tris(const Vector3d& c, double r, int n) {
  std::vector<Vector3d> v;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < n; ++j) {
      const double th = kPi * i / n, ph = 2 * kPi * j / n;
      const double st = i == 0 || i == n ? 0.0 : std::sin(th);  // poles: one point each
      v.push_back(c + r * Vector3d(st * std::cos(ph), st * std::sin(ph), std::cos(th)));
    }
  for (auto& p : v) p = p.cast<float>().cast<double>();
  auto at = [&](int i, int j) { return v[static_cast<std::size_t>(i * n + (j % n))]; };
  std::vector<Tri> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i > 0) t.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i < n - 1) t.push_back({at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
    }
  return t;
}

ShapeSpec mesh_spec(const std::string& file, int line) {
  ShapeSpec s;
  s.type = ShapeSpec::Type::Mesh;
  s.file = file;
  s.line = line;
  return s;
}

TEST(MeshFill, BoxStlCountsEqualAnalyticVolume) {
  write_binary_stl((temp_dir() / "box.stl").string(),
                   box_tris(Vector3d(0.1, 0.2, 0.0), Vector3d(0.5, 0.4, 0.3)));
  std::vector<MeshReport> reports;
  const ShapePtr m = build_shape(mesh_spec("box.stl", 4), 3, temp_dir().string(), &reports);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].faces, 12u);
  const auto f = fill({fluid("m", m)}, 3, 0.01);
  EXPECT_EQ(f[0].points.size(), 40u * 20 * 30);
  EXPECT_NEAR(f[0].report.volume_error(3, 0.01), 0.0, 1e-6);  // float32 STL coordinates

  // 2D: the section y = 0.3 is the (x, z) rectangle 0.4 x 0.3.
  ShapeSpec s2 = mesh_spec("box.stl", 7);
  s2.slice_y = 0.3;
  const ShapePtr sec = build_shape(s2, 2, temp_dir().string());
  EXPECT_NEAR(sec->volume(), 0.12, 1e-6);
  EXPECT_EQ(fill({fluid("s", sec)}, 2, 0.01)[0].points.size(), 40u * 30);
  // Errors name the line.
  try {
    build_shape(mesh_spec("box.stl", 7), 2, temp_dir().string());
    ADD_FAILURE() << "no slice_y accepted in 2D";
  } catch (const ShapeError& e) {
    EXPECT_EQ(e.line(), 7);
    EXPECT_NE(std::string(e.what()).find("line 7: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("slice_y"), std::string::npos) << e.what();
  }
  s2.slice_y = 0.9;
  EXPECT_THROW(build_shape(s2, 2, temp_dir().string()), ShapeError);
  EXPECT_THROW(build_shape(mesh_spec("missing.stl", 3), 3, temp_dir().string()),
               std::invalid_argument);
}

TEST(MeshFill, SphereStlCountMatchesMeshVolume) {
  const double r = 0.3, dp = 0.02;
  write_binary_stl((temp_dir() / "ball.stl").string(), sphere_tris(Vector3d(0.05, 0, 0.1), r, 64));
  std::vector<MeshReport> reports;
  const ShapePtr m = build_shape(mesh_spec("ball.stl", 2), 3, temp_dir().string(), &reports);
  const auto f = fill({fluid("ball", m)}, 3, dp);
  const double v = reports.at(0).volume, area = 4 * kPi * r * r;
  EXPECT_NEAR(m->volume(), v, 1e-12);
  EXPECT_LE(std::abs(f[0].points.size() * std::pow(dp, 3) - v), 0.5 * area * dp);
  // The same fill in a tank with the mesh as an obstacle: no overlap.
  std::vector<BodyGeometry> b = {
      wall("tank", box(Vector3d(-0.5, -0.5, -0.3), Vector3d(0.6, 0.5, 0.5), 3), true, 2),
      wall("ball", m, false, 2),
      fluid("water", box(Vector3d(-0.5, -0.5, -0.3), Vector3d(0.6, 0.5, 0.3), 3))};
  const auto g = fill(b, 3, dp);
  EXPECT_GE(min_distance_across_bodies(g, dp), 0.99 * dp);
}

TEST(MeshFill, TimedMillionParticleSphere) {
  // ~1e5 faces; radius such that (4/3) pi (r/dp)^3 ~ 1e6.
  const double dp = 0.01, r = 0.62;
  const std::string file = (temp_dir() / "big_ball.stl").string();
  write_binary_stl(file, sphere_tris(Vector3d(0.003, -0.002, 0.001), r, 224));
  std::vector<MeshReport> reports;
  auto t0 = std::chrono::steady_clock::now();
  const ShapePtr m = build_shape(mesh_spec("big_ball.stl", 1), 3, temp_dir().string(), &reports);
  auto t1 = std::chrono::steady_clock::now();
  const auto f = fill({fluid("ball", m)}, 3, dp);
  auto t2 = std::chrono::steady_clock::now();
  const double v = reports.at(0).volume, area = 4 * kPi * r * r;
  EXPECT_LE(std::abs(f[0].points.size() * std::pow(dp, 3) - v), 0.5 * area * dp);
  std::cout << "  sphere STL " << reports[0].faces << " faces: load "
            << std::chrono::duration<double>(t1 - t0).count() << " s, fill " << f[0].points.size()
            << " particles in " << std::chrono::duration<double>(t2 - t1).count() << " s ("
            << omp_get_max_threads()
            << " threads), N dp^3 / V - 1 = " << f[0].report.volume_error(3, dp) << "\n";
}

// ------------------------------------------------------------------------- case and command

TEST(FillCommand, CaseWithMeshAndFillBelowMatchesSetupAndWritesNames) {
  write_binary_stl((temp_dir() / "rock.stl").string(),
                   box_tris(Vector3d(0.4, 0.0, 0.0), Vector3d(0.6, 0.2, 0.1)));
  const std::string text =
      "name: rocks\ndim: 3\ndp: 0.02\ntime: {end: 1}\nbodies:\n"
      "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0, 0], max: [1, 0.4, 0.5]}},"
      " open: [zmax]}\n"
      "  - {name: rock, kind: boundary, walls: outside, layers: 2,"
      " shape: {mesh: {file: rock.stl}}}\n"
      "  - {name: water, kind: fluid, fill: {below: 0.3, inside: tank}}\n";
  const CaseSpec spec = parse_case_text(text, (temp_dir() / "rocks.yaml").string());
  const CaseSetup<3> setup = setup_case<3>(spec);
  ASSERT_EQ(setup.fill.size(), 3u);
  ASSERT_EQ(setup.meshes.size(), 1u);
  EXPECT_EQ(setup.meshes[0].faces, 12u);
  // The aligned rock removes exactly its own cells from the 50 x 20 x 15 still water (its
  // float32 STL coordinates lie up to 3e-8 m outside the aligned faces: gap tolerance).
  EXPECT_EQ(setup.fill[2].particles, 50u * 20 * 15 - 10 * 10 * 5);
  EXPECT_EQ(setup.fill[2].in_region, 50u * 20 * 15);
  EXPECT_NEAR(setup.fill[2].volume_error(3, 0.02), 0.0, 1e-12);

  std::ostringstream log;
  FillCommandOptions opt;
  opt.out_dir = (temp_dir() / "out").string();
  const FillSummary sum = run_fill(spec, opt, log);
  EXPECT_EQ(sum.fluid, setup.fill[2].particles);
  EXPECT_EQ(sum.fluid + sum.boundary, setup.particles.size());
  EXPECT_NE(log.str().find("body water (fluid, below z = 0.3 inside 'tank'): 14500 particles"),
            std::string::npos)
      << log.str();
  EXPECT_NE(log.str().find("mesh "), std::string::npos) << log.str();
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(sum.vtp.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  ASSERT_EQ(static_cast<std::size_t>(poly->GetNumberOfPoints()), setup.particles.size());
  auto* names = vtkStringArray::SafeDownCast(poly->GetPointData()->GetAbstractArray("body_name"));
  ASSERT_NE(names, nullptr);
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
    ASSERT_EQ(names->GetValue(i),
              setup.bodies[setup.particles.body[static_cast<std::size_t>(i)]].name);

  // A shape error names the case file and the line.
  std::string bad = text;
  bad.replace(bad.find("rock.stl"), 8, "nothere.stl");
  try {
    setup_case<3>(parse_case_text(bad, (temp_dir() / "bad.yaml").string()));
    ADD_FAILURE() << "a missing mesh file was accepted";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml:7: bodies[1].shape"), std::string::npos)
        << e.what();
  }
}

// `fill: below` with structures: the volume check compares the particles with the water the
// tank really holds, region less structures (a 1:10 ramp and a box here, areas known exactly),
// and the lattice's staircase along the ramp leaves a void of at most 1 dp over the structures'
// wetted perimeter.
TEST(FillCommand, FillBelowVolumeCheckCutsOutStructures) {
  std::filesystem::create_directories(temp_dir());
  for (const double dp : {0.01, 0.005}) {
    std::ostringstream text;
    text << "name: ramp\ndim: 2\ndp: " << dp << "\ntime: {end: 1}\nbodies:\n"
         << "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [2, 0.5]}}, "
            "open: [ymax]}\n"
         << "  - {name: ramp, kind: boundary, walls: outside, shape: {polygon: {points: "
            "[[0.5, 0], [2, 0], [2, 0.15]]}}}\n"
         << "  - {name: block, kind: boundary, walls: outside, shape: {box: {min: [0.2, 0], "
            "max: [0.3, 0.1]}}}\n"
         << "  - {name: water, kind: fluid, fill: {below: 0.3, inside: tank}}\n";
    const CaseSpec spec = parse_case_text(text.str(), (temp_dir() / "ramp.yaml").string());
    std::ostringstream log;
    FillCommandOptions opt;
    opt.out_dir = (temp_dir() / "ramp_out").string();
    const FillSummary sum = run_fill(spec, opt, log);
    ASSERT_EQ(sum.volumes.size(), 1u);
    const FluidVolumeCheck& v = sum.volumes[0];
    const double ramp = 0.5 * 1.5 * 0.15, block = 0.1 * 0.1;
    const double water = 2.0 * 0.3 - ramp - block;
    // Wetted perimeter of the structures: the ramp's slope and the block's three faces.
    const double perimeter = std::hypot(1.5, 0.15) + 0.3;
    EXPECT_DOUBLE_EQ(v.region, 0.6);
    EXPECT_NEAR(v.lattice, 0.6, 1e-12);  // the lattice before the cut: the old, wrong check
    EXPECT_NEAR(v.structures, ramp + block, v.spacing * perimeter) << log.str();
    EXPECT_NEAR(v.water(), water, v.spacing * perimeter);
    EXPECT_DOUBLE_EQ(v.particles, static_cast<double>(sum.fluid) * dp * dp);
    // The particles fill the water but for the staircase: a void, and under 1 dp x perimeter.
    EXPECT_GT(v.void_volume(), 0.0);
    EXPECT_LT(v.void_volume(), dp * perimeter) << log.str();
    EXPECT_NE(log.str().find("water = region 0.6 m^2 - structures"), std::string::npos)
        << log.str();
    EXPECT_NE(log.str().find("void:"), std::string::npos) << log.str();
    std::printf(
        "[ measured ] dp %g: water %.6f m^2 (exact %.6f), particles %.6f m^2, void %.6f "
        "m^2 = %.2f dp over the %.3f m wetted perimeter\n",
        dp, v.water(), water, v.particles, v.void_volume(), v.void_volume() / (dp * perimeter),
        perimeter);
  }
}

}  // namespace
}  // namespace swell::geometry
