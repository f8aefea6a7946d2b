// MeshSolid: reading STL (ASCII, binary), OBJ, OFF and PLY; placement; the closed,
// self-intersection and orientation checks and their repairs; inside/outside and signed
// distance against exact answers; volume against independently computed polyhedron volumes;
// y-slices; concurrent queries. The mesh files are written by the test into a temp folder.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "geometry/mesh_solid.hpp"

namespace fs = std::filesystem;
using Eigen::Vector3d;
using swell::Placement;
using swell::geometry::MeshError;
using swell::geometry::MeshReport;
using swell::geometry::MeshSolid;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct TriMesh {
  std::vector<Vector3d> v;
  std::vector<std::array<int, 3>> f;
  std::vector<std::array<int, 4>> quads;  // box_mesh only: the sides as outward quads
};

// A folder of its own per test program, removed at the end.
const fs::path& temp_dir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("swell_test_mesh_solid_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

class TempDirCleanup : public ::testing::Environment {
 public:
  void TearDown() override { fs::remove_all(temp_dir()); }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new TempDirCleanup);

std::string path_of(const std::string& name) {
  return (temp_dir() / name).string();
}

// Adds the quad a-b-c-d as two triangles whose normal points along `outward`.
void add_quad(TriMesh& m, int a, int b, int c, int d, const Vector3d& outward) {
  const Vector3d n = (m.v[b] - m.v[a]).cross(m.v[c] - m.v[a]);
  if (n.dot(outward) < 0) std::swap(b, d);
  m.f.push_back({a, b, c});
  m.f.push_back({a, c, d});
  m.quads.push_back({a, b, c, d});
}

TriMesh box_mesh(const Vector3d& lo, const Vector3d& hi) {
  TriMesh m;
  for (int i = 0; i < 8; ++i)
    m.v.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  add_quad(m, 0, 2, 6, 4, -Vector3d::UnitX());
  add_quad(m, 1, 3, 7, 5, Vector3d::UnitX());
  add_quad(m, 0, 1, 5, 4, -Vector3d::UnitY());
  add_quad(m, 2, 3, 7, 6, Vector3d::UnitY());
  add_quad(m, 0, 1, 3, 2, -Vector3d::UnitZ());
  add_quad(m, 4, 5, 7, 6, Vector3d::UnitZ());
  return m;
}

// Icosahedron subdivided `levels` times, vertices projected on the sphere: 20 * 4^levels faces.
TriMesh icosphere(const Vector3d& center, double r, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vector3d> u = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                             {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                             {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : u) p.normalize();
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      u.push_back((u[a] + u[b]).normalized());
      return mid[key] = static_cast<int>(u.size()) - 1;
    };
    std::vector<std::array<int, 3>> g;
    for (const auto& tri : f) {
      const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                c = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], c, b});
      g.push_back({a, b, c});
    }
    f = std::move(g);
  }
  TriMesh m;
  for (const auto& p : u) m.v.push_back(center + r * p);
  for (auto tri : f) {  // orient outward
    const Vector3d n = (u[tri[1]] - u[tri[0]]).cross(u[tri[2]] - u[tri[0]]);
    if (n.dot(u[tri[0]] + u[tri[1]] + u[tri[2]]) < 0) std::swap(tri[1], tri[2]);
    m.f.push_back(tri);
  }
  return m;
}

// Divergence theorem: sum of signed tetrahedra from the origin.
double polyhedron_volume(const TriMesh& m) {
  double v = 0.0;
  for (const auto& t : m.f) v += m.v[t[0]].dot(m.v[t[1]].cross(m.v[t[2]])) / 6.0;
  return v;
}

TriMesh reversed(TriMesh m) {
  for (auto& t : m.f) std::swap(t[1], t[2]);
  return m;
}

TriMesh merged(const TriMesh& a, const TriMesh& b) {
  TriMesh m = a;
  const int off = static_cast<int>(a.v.size());
  m.v.insert(m.v.end(), b.v.begin(), b.v.end());
  for (auto t : b.f) m.f.push_back({t[0] + off, t[1] + off, t[2] + off});
  return m;
}

std::string write_ascii_stl(const TriMesh& m, const std::string& name) {
  const std::string path = path_of(name);
  std::ofstream os(path);
  os.precision(17);
  os << "solid test\n";
  for (const auto& t : m.f) {
    const Vector3d n = (m.v[t[1]] - m.v[t[0]]).cross(m.v[t[2]] - m.v[t[0]]).normalized();
    os << " facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n  outer loop\n";
    for (int k : t)
      os << "   vertex " << m.v[k].x() << ' ' << m.v[k].y() << ' ' << m.v[k].z() << '\n';
    os << "  endloop\n endfacet\n";
  }
  os << "endsolid test\n";
  return path;
}

std::string write_binary_stl(const TriMesh& m, const std::string& name) {
  const std::string path = path_of(name);
  std::ofstream os(path, std::ios::binary);
  char header[80] = "binary STL written by test_mesh_solid";
  os.write(header, 80);
  const std::uint32_t n = static_cast<std::uint32_t>(m.f.size());
  os.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.f) {
    const Vector3d nn = (m.v[t[1]] - m.v[t[0]]).cross(m.v[t[2]] - m.v[t[0]]).normalized();
    float rec[12] = {float(nn.x()), float(nn.y()), float(nn.z())};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) rec[3 + 3 * k + d] = static_cast<float>(m.v[t[k]][d]);
    os.write(reinterpret_cast<const char*>(rec), sizeof rec);
    const std::uint16_t attr = 0;
    os.write(reinterpret_cast<const char*>(&attr), 2);
  }
  return path;
}

std::string write_off(const TriMesh& m, const std::string& name) {
  const std::string path = path_of(name);
  std::ofstream os(path);
  os.precision(17);
  os << "OFF\n" << m.v.size() << ' ' << m.f.size() << " 0\n";
  for (const auto& p : m.v) os << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const auto& t : m.f) os << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  return path;
}

std::string write_obj(const TriMesh& m, const std::string& name) {
  const std::string path = path_of(name);
  std::ofstream os(path);
  os.precision(17);
  for (const auto& p : m.v) os << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const auto& t : m.f) os << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  return path;
}

std::string write_ply(const TriMesh& m, const std::string& name) {
  const std::string path = path_of(name);
  std::ofstream os(path);
  os.precision(17);
  os << "ply\nformat ascii 1.0\nelement vertex " << m.v.size()
     << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << m.f.size()
     << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : m.v) os << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const auto& t : m.f) os << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  return path;
}

// Loads and returns the MeshError message, or "" if it loaded.
std::string load_error(const std::string& path, bool repair = false) {
  try {
    MeshSolid::load(path, Placement{}, repair);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

double shoelace(const std::vector<Eigen::Vector2d>& loop) {
  double a = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto& p = loop[i];
    const auto& q = loop[(i + 1) % loop.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

// Exact Euclidean distance from an inside point to the surface of an axis-aligned box.
double inside_box_distance(const Vector3d& p, const Vector3d& lo, const Vector3d& hi) {
  return std::min((p - lo).minCoeff(), (hi - p).minCoeff());
}

// The box used throughout: corners exactly representable in float (binary STL).
const Vector3d kLo(-0.5, 0.25, 1.0), kHi(1.5, 1.0, 2.5);
const double kBoxVolume = 2.0 * 0.75 * 1.5;

void expect_box_solid(const MeshSolid& s, const Vector3d& lo, const Vector3d& hi) {
  const double vol = (hi - lo).prod();
  EXPECT_NEAR(s.volume(), vol, 1e-12 * vol);
  EXPECT_TRUE(s.bounds().min.isApprox(lo, 1e-15));
  EXPECT_TRUE(s.bounds().max.isApprox(hi, 1e-15));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Vector3d p = lo + (hi - lo).cwiseProduct(Vector3d(u(rng), u(rng), u(rng)));
    EXPECT_TRUE(s.contains(p)) << p.transpose();
    EXPECT_NEAR(s.signed_distance(p), -inside_box_distance(p, lo, hi), 1e-12);
  }
  const Vector3d c = 0.5 * (lo + hi);
  EXPECT_FALSE(s.contains(Vector3d(hi.x() + 0.01, c.y(), c.z())));
  EXPECT_FALSE(s.contains(Vector3d(c.x(), lo.y() - 1e-6, c.z())));
  EXPECT_FALSE(s.contains(Vector3d(100, 100, 100)));
  // Outside: beside a face, and off a corner (distance to the corner).
  EXPECT_NEAR(s.signed_distance(Vector3d(c.x(), c.y(), hi.z() + 0.3)), 0.3, 1e-12);
  EXPECT_NEAR(s.signed_distance(hi + Vector3d(0.1, 0.2, 0.2)), 0.3, 1e-12);
  // On the surface counts as inside.
  EXPECT_TRUE(s.contains(Vector3d(hi.x(), c.y(), c.z())));
}

}  // namespace

TEST(MeshSolid, AsciiStlBox) {
  const std::string path = write_ascii_stl(box_mesh(kLo, kHi), "box_ascii.stl");
  MeshReport rep;
  const auto s = MeshSolid::load(path, Placement{}, false, &rep);
  expect_box_solid(*s, kLo, kHi);
  EXPECT_EQ(rep.file, path);
  EXPECT_EQ(rep.vertices, 8u);
  EXPECT_EQ(rep.faces, 12u);
  EXPECT_TRUE(rep.closed);
  EXPECT_EQ(rep.border_edges, 0u);
  EXPECT_EQ(rep.self_intersections, 0u);
  EXPECT_FALSE(rep.reoriented);
  EXPECT_TRUE(rep.repairs.empty());
  EXPECT_NEAR(rep.volume, kBoxVolume, 1e-12 * kBoxVolume);
  EXPECT_EQ(s->describe(), "mesh box_ascii.stl (12 faces)");
  EXPECT_EQ(s->report().faces, 12u);
}

TEST(MeshSolid, BinaryStlBox) {
  const std::string path = write_binary_stl(box_mesh(kLo, kHi), "box_binary.stl");
  const auto s = MeshSolid::load(path, Placement{}, false);
  expect_box_solid(*s, kLo, kHi);
  EXPECT_EQ(s->report().vertices, 8u);
}

TEST(MeshSolid, OtherFormatsAndUpperCaseExtension) {
  const TriMesh box = box_mesh(kLo, kHi);
  for (const std::string& path :
       {write_obj(box, "box.obj"), write_off(box, "box.off"), write_ply(box, "box.ply"),
        write_ascii_stl(box, "BOX.STL"), write_off(box, "box.Off")}) {
    SCOPED_TRACE(path);
    const auto s = MeshSolid::load(path, Placement{}, false);
    expect_box_solid(*s, kLo, kHi);
  }
  // Quads in an OBJ are triangulated.
  const std::string quads = path_of("box_quads.obj");
  {
    std::ofstream os(quads);
    for (const auto& p : box.v) os << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (const auto& q : box.quads)
      os << "f " << q[0] + 1 << ' ' << q[1] + 1 << ' ' << q[2] + 1 << ' ' << q[3] + 1 << '\n';
  }
  const auto s = MeshSolid::load(quads, Placement{}, false);
  EXPECT_EQ(s->report().faces, 12u);
  expect_box_solid(*s, kLo, kHi);
}

TEST(MeshSolid, UnreadableFilesNameTheFileAndTheFormats) {
  const std::string unknown = path_of("box.xyz");
  std::ofstream(unknown) << "1 2 3\n";
  std::string msg = load_error(unknown);
  EXPECT_NE(msg.find(unknown), std::string::npos) << msg;
  EXPECT_NE(msg.find(".stl"), std::string::npos) << msg;
  EXPECT_NE(msg.find(".ply"), std::string::npos) << msg;

  const std::string missing = path_of("missing.stl");
  msg = load_error(missing);
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;

  const std::string garbage = path_of("garbage.off");
  std::ofstream(garbage) << "this is not an OFF file\n";
  msg = load_error(garbage);
  EXPECT_NE(msg.find(garbage), std::string::npos) << msg;
  EXPECT_NE(msg.find(".obj"), std::string::npos) << msg;
}

TEST(MeshSolid, IcosphereVolumeIsThePolyhedronVolume) {
  const Vector3d c(0.3, -0.2, 1.1);
  const double r = 0.7;
  const TriMesh sphere = icosphere(c, r, 3);  // 1280 faces
  const double exact = polyhedron_volume(sphere);
  const double ball = 4.0 / 3.0 * kPi * r * r * r;
  ASSERT_LT(exact, ball);
  ASSERT_GT(exact, 0.97 * ball);
  for (const std::string& path :
       {write_off(sphere, "sphere.off"), write_obj(sphere, "sphere.obj")}) {
    SCOPED_TRACE(path);
    const auto s = MeshSolid::load(path, Placement{}, false);
    EXPECT_EQ(s->report().faces, 1280u);
    EXPECT_FALSE(s->report().reoriented);
    EXPECT_NEAR(s->volume(), exact, 1e-12 * exact);
    EXPECT_TRUE(s->contains(c));
    EXPECT_FALSE(s->contains(c + Vector3d(0, 0, 1.01 * r)));
    const double d = s->signed_distance(c);
    EXPECT_LE(d, -0.98 * r);
    EXPECT_GE(d, -r);
  }
}

TEST(MeshSolid, PlacementScalesRotatesThenTranslates) {
  const std::string path = write_ascii_stl(box_mesh(kLo, kHi), "box_placed.stl");
  Placement pl;
  pl.scale = Vector3d::Constant(2.0);
  pl.rotate_deg = Vector3d(0, 0, 90);
  pl.translate = Vector3d(1, 2, 3);
  const auto s = MeshSolid::load(path, pl, false);
  // Scale 2, then (x, y) -> (-y, x), then translate.
  const Vector3d lo(-2 * kHi.y() + 1, 2 * kLo.x() + 2, 2 * kLo.z() + 3);
  const Vector3d hi(-2 * kLo.y() + 1, 2 * kHi.x() + 2, 2 * kHi.z() + 3);
  EXPECT_TRUE((s->bounds().min - lo).cwiseAbs().maxCoeff() < 1e-12) << s->bounds().min.transpose();
  EXPECT_TRUE((s->bounds().max - hi).cwiseAbs().maxCoeff() < 1e-12) << s->bounds().max.transpose();
  EXPECT_NEAR(s->volume(), 8 * kBoxVolume, 1e-12 * 8 * kBoxVolume);
  EXPECT_TRUE(s->contains(0.5 * (lo + hi)));
  EXPECT_FALSE(
      s->contains(Vector3d(0.5 * (lo.x() + hi.x()), hi.y() + 0.01, 0.5 * (lo.z() + hi.z()))));

  // Order of the rotations: about x first, then y. Rx(90): (x,y,z) -> (x,-z,y);
  // Ry(90): (x,y,z) -> (z,y,-x); together (x,y,z) -> (y,-z,-x).
  Placement xy;
  xy.rotate_deg = Vector3d(90, 90, 0);
  const auto r = MeshSolid::load(path, xy, false);
  const Vector3d rlo(kLo.y(), -kHi.z(), -kHi.x()), rhi(kHi.y(), -kLo.z(), -kLo.x());
  EXPECT_TRUE((r->bounds().min - rlo).cwiseAbs().maxCoeff() < 1e-12) << r->bounds().min.transpose();
  EXPECT_TRUE((r->bounds().max - rhi).cwiseAbs().maxCoeff() < 1e-12) << r->bounds().max.transpose();
  EXPECT_NEAR(r->volume(), kBoxVolume, 1e-12 * kBoxVolume);

  // A mirror (negative scale) turns the normals inward; the load orients them back.
  Placement mirror;
  mirror.scale = Vector3d(-1, 1, 1);
  const auto m = MeshSolid::load(path, mirror, false);
  EXPECT_TRUE(m->report().reoriented);
  EXPECT_NEAR(m->volume(), kBoxVolume, 1e-12 * kBoxVolume);
}

TEST(MeshSolid, MissingFaceIsAnErrorUnlessRepaired) {
  TriMesh box = box_mesh(kLo, kHi);
  box.f.erase(box.f.begin() + 5);
  const std::string path = write_ascii_stl(box, "box_hole.stl");
  const std::string msg = load_error(path);
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("not closed"), std::string::npos) << msg;
  EXPECT_NE(msg.find("3 border edges around 1 hole"), std::string::npos) << msg;
  EXPECT_NE(msg.find("repair: true"), std::string::npos) << msg;

  MeshReport rep;
  const auto s = MeshSolid::load(path, Placement{}, true, &rep);
  EXPECT_TRUE(rep.closed);
  EXPECT_EQ(rep.border_edges, 3u);
  ASSERT_FALSE(rep.repairs.empty());
  bool filled = false;
  for (const auto& line : rep.repairs) filled |= line.find("filled 1 hole") != std::string::npos;
  EXPECT_TRUE(filled) << rep.repairs.front();
  EXPECT_NEAR(s->volume(), kBoxVolume, 1e-9 * kBoxVolume);
  expect_box_solid(*s, kLo, kHi);

  // A whole side missing (two triangles): one 4-edge hole.
  TriMesh open = box_mesh(kLo, kHi);
  open.f.erase(open.f.begin() + 2, open.f.begin() + 4);
  const std::string open_path = write_off(open, "box_open.off");
  EXPECT_NE(load_error(open_path).find("4 border edges around 1 hole"), std::string::npos);
  const auto o = MeshSolid::load(open_path, Placement{}, true);
  EXPECT_NEAR(o->volume(), kBoxVolume, 1e-9 * kBoxVolume);
}

TEST(MeshSolid, SoupCleanupIsReportedWhenRepairing) {
  TriMesh box = box_mesh(kLo, kHi);
  box.f.push_back(box.f[0]);  // a duplicated face
  const std::string path = write_off(box, "box_duplicate_face.off");
  MeshReport rep;
  const auto s = MeshSolid::load(path, Placement{}, true, &rep);
  EXPECT_EQ(rep.faces, 12u);
  ASSERT_EQ(rep.repairs.size(), 1u);
  EXPECT_NE(rep.repairs[0].find("13 -> 12 faces"), std::string::npos) << rep.repairs[0];
  EXPECT_NEAR(s->volume(), kBoxVolume, 1e-12 * kBoxVolume);
}

TEST(MeshSolid, InvertedNormalsAreReoriented) {
  const std::string path = write_binary_stl(reversed(box_mesh(kLo, kHi)), "box_inverted.stl");
  MeshReport rep;
  const auto s = MeshSolid::load(path, Placement{}, false, &rep);
  EXPECT_TRUE(rep.reoriented);
  EXPECT_GT(s->volume(), 0.0);
  expect_box_solid(*s, kLo, kHi);
}

TEST(MeshSolid, HollowBodyIsOrientedByNesting) {
  // A box with a box-shaped cavity, the cavity's normals pointing the wrong way (outward of
  // the cavity, i.e. into the void).
  const Vector3d ilo(0, 0.5, 1.5), ihi(1, 0.75, 2);
  const TriMesh hollow = merged(box_mesh(kLo, kHi), box_mesh(ilo, ihi));
  MeshReport rep;
  const auto s = MeshSolid::load(write_off(hollow, "hollow.off"), Placement{}, false, &rep);
  EXPECT_TRUE(rep.reoriented);
  const double vol = kBoxVolume - (ihi - ilo).prod();
  EXPECT_NEAR(s->volume(), vol, 1e-12 * vol);
  EXPECT_FALSE(s->contains(0.5 * (ilo + ihi)));
  EXPECT_TRUE(s->contains(Vector3d(1.2, 0.5, 1.7)));
  EXPECT_NEAR(s->signed_distance(0.5 * (ilo + ihi)), 0.125, 1e-12);
}

TEST(MeshSolid, OverlappingBoxesAreSelfIntersecting) {
  const TriMesh two = merged(box_mesh(Vector3d(0, 0, 0), Vector3d(1, 1, 1)),
                             box_mesh(Vector3d(0.5, 0.3, 0.2), Vector3d(1.5, 1.2, 1.4)));
  const std::string path = write_ascii_stl(two, "two_boxes.stl");
  const std::string msg = load_error(path);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(msg, m, std::regex("(\\d+) pairs of faces intersect"))) << msg;
  EXPECT_GT(std::stoi(m[1]), 0);
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("repair: true"), std::string::npos) << msg;

  // With repair, CGAL's local removal fails and autorefinement gives the union.
  MeshReport rep;
  const auto s = MeshSolid::load(path, Placement{}, true, &rep);
  EXPECT_EQ(rep.self_intersections, static_cast<std::size_t>(std::stoi(m[1])));
  EXPECT_TRUE(rep.closed);
  ASSERT_EQ(rep.repairs.size(), 1u);
  EXPECT_NE(rep.repairs[0].find("autorefinement"), std::string::npos) << rep.repairs[0];
  const double uni = 1.0 + 1.0 * 0.9 * 1.2 - 0.5 * 0.7 * 0.8;
  EXPECT_NEAR(s->volume(), uni, 1e-12 * uni);
  EXPECT_TRUE(s->contains(Vector3d(0.75, 0.6, 0.6)));   // in both
  EXPECT_TRUE(s->contains(Vector3d(1.25, 0.6, 0.6)));   // in the second only
  EXPECT_FALSE(s->contains(Vector3d(1.25, 0.1, 0.6)));  // in neither
}

TEST(MeshSolid, SliceOfABoxIsItsSection) {
  const auto s =
      MeshSolid::load(write_off(box_mesh(kLo, kHi), "box_slice.off"), Placement{}, false);
  const auto loops = s->slice_y(0.6);
  ASSERT_EQ(loops.size(), 1u);
  const double area = (kHi.x() - kLo.x()) * (kHi.z() - kLo.z());
  EXPECT_NEAR(std::abs(shoelace(loops[0])), area, 1e-12 * area);
  for (const auto& p : loops[0]) {
    EXPECT_GE(p.x(), kLo.x() - 1e-12);
    EXPECT_LE(p.y(), kHi.z() + 1e-12);
  }
  EXPECT_TRUE(s->slice_y(kHi.y() + 0.1).empty());
  EXPECT_TRUE(s->slice_y(kLo.y() - 0.1).empty());
}

TEST(MeshSolid, SliceOfASphereIsNearlyACircle) {
  const double r = 0.5, y0 = 0.2;
  const auto s = MeshSolid::load(write_off(icosphere(Vector3d::Zero(), r, 5), "sphere5.off"),
                                 Placement{}, false);
  const auto loops = s->slice_y(y0);
  ASSERT_EQ(loops.size(), 1u);
  const double area = std::abs(shoelace(loops[0]));
  const double disc = kPi * (r * r - y0 * y0);
  // The polyhedron is inscribed in the sphere, so its section is inside the disc.
  EXPECT_LE(area, disc);
  EXPECT_GT(area, (1 - 3e-3) * disc);
}

TEST(MeshSolid, ConcurrentQueriesEqualSerialOnes) {
  const auto s = MeshSolid::load(
      write_off(icosphere(Vector3d(0.1, 0.2, 0.3), 1.0, 4), "sphere4.off"), Placement{}, false);
  const int n = 100000;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  std::vector<Vector3d> pts(n);
  for (auto& p : pts) p = Vector3d(0.1 + u(rng), 0.2 + u(rng), 0.3 + u(rng));
  std::vector<char> in_serial(n), in_parallel(n);
  std::vector<double> d_serial(n), d_parallel(n), w_serial(n), w_parallel(n);
  for (int i = 0; i < n; ++i) {
    in_serial[i] = s->contains(pts[i]);
    d_serial[i] = s->signed_distance(pts[i]);
    w_serial[i] = s->signed_distance_within(pts[i], 0.05);
  }
#pragma omp parallel for schedule(dynamic, 256) num_threads(4)
  for (int i = 0; i < n; ++i) {
    in_parallel[i] = s->contains(pts[i]);
    d_parallel[i] = s->signed_distance(pts[i]);
    w_parallel[i] = s->signed_distance_within(pts[i], 0.05);
  }
  EXPECT_EQ(in_serial, in_parallel);
  EXPECT_EQ(d_serial, d_parallel);
  EXPECT_EQ(w_serial, w_parallel);
  int inside = 0;
  for (char c : in_serial) inside += c;
  // About 4/3 pi / 2.4^3 = 30 % of the cube is inside the unit ball.
  EXPECT_GT(inside, n / 4);
  EXPECT_LT(inside, n / 3);
}

TEST(MeshSolid, DistanceSearchesAgreeWithCgal) {
  const auto s = MeshSolid::load(
      write_off(icosphere(Vector3d(0.1, 0.2, 0.3), 1.0, 3), "sphere3.off"), Placement{}, false);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  int band = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vector3d p(0.1 + u(rng), 0.2 + u(rng), 0.3 + u(rng));
    const double d = s->signed_distance(p);
    EXPECT_NEAR(d, s->signed_distance_cgal(p), 1e-14) << p.transpose();
    EXPECT_EQ(d < 0, s->contains(p));
    const double w = s->signed_distance_within(p, 0.1);
    if (std::abs(d) < 0.1) {
      EXPECT_NEAR(w, d, 1e-14);
      ++band;
    } else {
      EXPECT_EQ(w, d < 0 ? -0.1 : 0.1);
    }
  }
  EXPECT_GT(band, 1000);
}

// Not a check: prints how long 1e6 queries take against a ~1e5-face mesh with 2 threads
// (wall time, and process CPU time / 2, which is what an idle 2-core machine would take).
// About a minute, so disabled; run with
//   tests/test_mesh_solid --gtest_also_run_disabled_tests --gtest_filter='*Timing*'
TEST(MeshSolid, DISABLED_TimingOfAMillionQueries) {
  const TriMesh sphere = icosphere(Vector3d::Zero(), 1.0, 6);  // 81920 faces
  const std::string path = write_binary_stl(sphere, "sphere6.stl");
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  const auto s = MeshSolid::load(path, Placement{}, false);
  const double t_load = std::chrono::duration<double>(clock::now() - t0).count();
  std::printf("[ timing   ] %zu faces, load %.2f s; 1e6 points, 2 threads:\n", s->report().faces,
              t_load);

  const int n = 1000000;
  auto cpu_seconds = [] {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
  };
  auto run = [&](const char* what, const std::vector<Vector3d>& pts, auto&& query) {
    std::vector<double> out(pts.size());
    const auto t = clock::now();
    const double cpu = cpu_seconds();
#pragma omp parallel for schedule(dynamic, 1024) num_threads(2)
    for (std::size_t i = 0; i < pts.size(); ++i) out[i] = query(pts[i]);
    std::printf("[ timing   ]   %-58s %6.2f s wall, %6.2f s cpu/2\n", what,
                std::chrono::duration<double>(clock::now() - t).count(),
                0.5 * (cpu_seconds() - cpu));
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.1, 1.1);
  std::vector<Vector3d> box_pts(n), shell_pts(n);
  for (auto& p : box_pts) p = Vector3d(u(rng), u(rng), u(rng));
  std::uniform_real_distribution<double> band(0.95, 1.05);
  for (auto& p : shell_pts) p = Vector3d(u(rng), u(rng), u(rng)).normalized() * band(rng);

  run("uniform in the bounding box: contains", box_pts,
      [&](auto& p) { return double(s->contains(p)); });
  run("uniform in the bounding box: signed_distance (CGAL search)", box_pts,
      [&](auto& p) { return s->signed_distance_cgal(p); });
  run("uniform in the bounding box: signed_distance", box_pts,
      [&](auto& p) { return s->signed_distance(p); });
  run("uniform in the bounding box: signed_distance_within(0.05)", box_pts,
      [&](auto& p) { return s->signed_distance_within(p, 0.05); });
  run("shell |r - 1| < 0.05: contains", shell_pts, [&](auto& p) { return double(s->contains(p)); });
  run("shell |r - 1| < 0.05: signed_distance (CGAL search)", shell_pts,
      [&](auto& p) { return s->signed_distance_cgal(p); });
  run("shell |r - 1| < 0.05: signed_distance", shell_pts,
      [&](auto& p) { return s->signed_distance(p); });
  run("shell |r - 1| < 0.05: signed_distance_within(0.05)", shell_pts,
      [&](auto& p) { return s->signed_distance_within(p, 0.05); });
  SUCCEED();
}
