// Parsing of `bodies[i].shape` into ShapeSpec (geometry/shape_spec.hpp).
//
// A shape is a map with exactly one key naming its kind:
//   box:        {min: [..], max: [..]}
//   cylinder:   {center: [x, y], radius: r}                 2D: a disc
//               {p1: [x, y, z], p2: [x, y, z], radius: r}   3D: axis from p1 to p2
//   sphere:     {center: [..], radius: r}                   a disc in 2D
//   polygon:    {points: [[x, y], ...]}                     2D only; simple, >= 3 points
//   mesh (stl): {file: f.stl, scale: s | [sx, sy, sz], rotate: [rx, ry, rz], translate: [..3..],
//                repair: bool, slice_y: y}                  slice_y required in 2D, not in 3D
//   union:      [shape, shape, ...]                         >= 2 shapes
//   difference: [shape, shape, ...]                         the first minus the others
// Like the gauge reader, keys that belong to the other dimension's form of a shape are reported
// as such ("in a 2D case a cylinder is a disc") rather than as unknown keys.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "case/parse_util.hpp"
#include "case/schema.hpp"

namespace swell::case_parse {

namespace {

// The shape kinds and each kind's keys come from the schema (case/schema.cpp).
const Names& shape_kinds() {
  static const Names kinds = case_schema::all_keys("bodies[].shape");
  return kinds;
}
const Names kMeshExtensions = {".stl", ".obj", ".off", ".ply"};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool has_mesh_extension(const std::string& file) {
  const std::string name = lower(file);
  return std::any_of(kMeshExtensions.begin(), kMeshExtensions.end(), [&](std::string_view ext) {
    return name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0;
  });
}

// Twice the signed area of triangle (a, b, c) in the xy plane: > 0 when counter-clockwise.
double cross2(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

int sign_of(double v, double tol) {
  return v > tol ? 1 : (v < -tol ? -1 : 0);
}

// Whether closed segments pq and rs share a point (xy plane); `tol` bounds cross products taken
// as zero (collinear).
bool segments_meet(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                   const Eigen::Vector3d& s, double tol) {
  const int d1 = sign_of(cross2(p, q, r), tol), d2 = sign_of(cross2(p, q, s), tol);
  const int d3 = sign_of(cross2(r, s, p), tol), d4 = sign_of(cross2(r, s, q), tol);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;  // proper crossing
  // A point of one segment on the other (collinear cases included).
  const auto on_segment = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& x) {
    return std::min(a.x(), b.x()) <= x.x() && x.x() <= std::max(a.x(), b.x()) &&
           std::min(a.y(), b.y()) <= x.y() && x.y() <= std::max(a.y(), b.y());
  };
  return (d1 == 0 && on_segment(p, q, r)) || (d2 == 0 && on_segment(p, q, s)) ||
         (d3 == 0 && on_segment(r, s, p)) || (d4 == 0 && on_segment(r, s, q));
}

// A cylinder's keys in a `dim` ("2D", "3D") case, and those of `form` that `other` lacks.
Names cylinder_keys(std::string_view form) {
  return case_schema::keys_for("bodies[].shape.cylinder", form);
}
Names cylinder_keys_only(std::string_view form, std::string_view other) {
  Names out;
  for (const std::string_view k : cylinder_keys(form))
    if (!contains(cylinder_keys(other), k)) out.push_back(k);
  return out;
}

class ShapeReader : private NodeReader {
 public:
  explicit ShapeReader(const NodeReader& base) : NodeReader(base) {}

  ShapeSpec read(const YAML::Node& node, const std::string& path) const;

 private:
  ShapeSpec read_box(const YAML::Node& node, const std::string& path) const;
  ShapeSpec read_cylinder(const YAML::Node& node, const std::string& path) const;
  ShapeSpec read_sphere(const YAML::Node& node, const std::string& path) const;
  ShapeSpec read_polygon(const YAML::Node& key, const YAML::Node& node,
                         const std::string& path) const;
  ShapeSpec read_mesh(const YAML::Node& node, const std::string& path) const;
  ShapeSpec read_csg(ShapeSpec::Type type, const YAML::Node& node, const std::string& path) const;

  double radius(const YAML::Node& map, const std::string& path) const {
    return number_if(
        require(map, path, "radius"), child(path, "radius"), [](double r) { return r > 0.0; },
        "a number > 0");
  }
  // Fails on a key of `other_keys` (the other dimension's form of the shape) with `hint`, then
  // checks the keys against `allowed`.
  void check_dim_keys(const YAML::Node& node, const std::string& path, const Names& allowed,
                      const Names& other_keys, const std::string& hint) const;
  void check_polygon_points(const YAML::Node& points_node, const std::string& points_path,
                            const std::vector<Eigen::Vector3d>& points) const;
};

ShapeSpec ShapeReader::read(const YAML::Node& node, const std::string& path) const {
  expect(node.IsMap() && node.size() == 1, node, path,
         "a map with exactly one shape key (one of: " + join(shape_kinds()) + ")");
  const auto entry = *node.begin();
  const YAML::Node& key = entry.first;
  expect(key.IsScalar(), key, path, "a shape name");
  const std::string& kind = key.Scalar();
  const YAML::Node& value = entry.second;
  const std::string kind_path = child(path, kind);
  ShapeSpec shape;
  if (kind == "box") {
    shape = read_box(value, kind_path);
  } else if (kind == "cylinder") {
    shape = read_cylinder(value, kind_path);
  } else if (kind == "sphere") {
    shape = read_sphere(value, kind_path);
  } else if (kind == "polygon") {
    shape = read_polygon(key, value, kind_path);
  } else if (kind == "mesh" || kind == "stl") {
    shape = read_mesh(value, kind_path);
  } else if (kind == "union") {
    shape = read_csg(ShapeSpec::Type::Union, value, kind_path);
  } else if (kind == "difference") {
    shape = read_csg(ShapeSpec::Type::Difference, value, kind_path);
  } else {
    fail(key, "unknown shape '" + kind_path + "'; known shapes: " + join(shape_kinds()));
  }
  shape.line = line_of(node);
  return shape;
}

void ShapeReader::check_dim_keys(const YAML::Node& node, const std::string& path,
                                 const Names& allowed, const Names& other_keys,
                                 const std::string& hint) const {
  for (const auto& entry : node) {
    if (!entry.first.IsScalar() || !contains(other_keys, entry.first.Scalar())) continue;
    fail(entry.first, child(path, entry.first.Scalar()) + ": " + hint);
  }
  check_keys(node, path, allowed, " in a " + std::to_string(dim()) + "D case");
}

ShapeSpec ShapeReader::read_box(const YAML::Node& node, const std::string& path) const {
  expect_map(node, path, case_schema::all_keys("bodies[].shape.box"));
  const YAML::Node min_node = require(node, path, "min");
  const YAML::Node max_node = require(node, path, "max");
  ShapeSpec shape;
  shape.type = ShapeSpec::Type::Box;
  shape.box.min = vector(min_node, child(path, "min"));
  shape.box.max = vector(max_node, child(path, "max"));
  check_ordered(shape.box.min, shape.box.max, min_node, max_node, path);
  return shape;
}

ShapeSpec ShapeReader::read_cylinder(const YAML::Node& node, const std::string& path) const {
  ShapeSpec shape;
  shape.type = ShapeSpec::Type::Cylinder;
  if (dim() == 2) {
    expect(node.IsMap(), node, path, "a map such as {center: [x, y], radius: r}");
    check_dim_keys(node, path, cylinder_keys("2D"), cylinder_keys_only("3D", "2D"),
                   "in a 2D case a cylinder is a disc given by center and radius; the axis end "
                   "points p1 and p2 are for 3D cases");
    shape.p1 = vector(require(node, path, "center"), child(path, "center"));
    shape.p2 = shape.p1;
  } else {
    expect(node.IsMap(), node, path,
           "a map such as {p1: [x, y, z], p2: [x, y, z], radius: r} (the axis from p1 to p2)");
    check_dim_keys(node, path, cylinder_keys("3D"), cylinder_keys_only("2D", "3D"),
                   "in a 3D case a cylinder is given by the end points p1 and p2 of its axis and "
                   "its radius; 'center' is for 2D discs");
    shape.p1 = vector(require(node, path, "p1"), child(path, "p1"));
    const YAML::Node p2_node = require(node, path, "p2");
    shape.p2 = vector(p2_node, child(path, "p2"));
    if (shape.p1 == shape.p2) {
      fail(p2_node, child(path, "p2") +
                        ": p1 and p2 are the same point, but the cylinder axis runs from p1 to "
                        "p2, so they must differ");
    }
  }
  shape.radius = radius(node, path);
  return shape;
}

ShapeSpec ShapeReader::read_sphere(const YAML::Node& node, const std::string& path) const {
  expect_map(node, path, case_schema::all_keys("bodies[].shape.sphere"));
  ShapeSpec shape;
  shape.type = ShapeSpec::Type::Sphere;
  shape.p1 = vector(require(node, path, "center"), child(path, "center"));
  shape.radius = radius(node, path);
  return shape;
}

ShapeSpec ShapeReader::read_polygon(const YAML::Node& key, const YAML::Node& node,
                                    const std::string& path) const {
  if (dim() != 2) {
    fail(key, path +
                  ": polygons exist only in 2D cases; in a 3D case use a mesh (or a box, "
                  "cylinder or sphere)");
  }
  expect_map(node, path, case_schema::all_keys("bodies[].shape.polygon"));
  const YAML::Node points_node = require(node, path, "points");
  const std::string points_path = child(path, "points");
  expect(points_node.IsSequence() && points_node.size() >= 3, points_node, points_path,
         "a list of at least 3 points [x, y]");
  ShapeSpec shape;
  shape.type = ShapeSpec::Type::Polygon;
  for (std::size_t i = 0; i < points_node.size(); ++i) {
    shape.points.push_back(vector(points_node[i], item(points_path, i)));
  }
  check_polygon_points(points_node, points_path, shape.points);
  return shape;
}

// The polygon must be simple: no repeated consecutive points, a non-zero area, no crossing edges.
void ShapeReader::check_polygon_points(const YAML::Node& points_node,
                                       const std::string& points_path,
                                       const std::vector<Eigen::Vector3d>& points) const {
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t next = (i + 1) % n;
    if (points[i] != points[next]) continue;
    if (next == 0) {
      fail(points_node[n - 1], item(points_path, n - 1) +
                                   ": the last point repeats the first; a polygon closes "
                                   "itself, so leave the repeated point out");
    }
    fail(points_node[next], item(points_path, next) + ": the point repeats the previous one");
  }

  double extent = 0.0, twice_area = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    extent = std::max(extent, (points[i] - points[0]).cwiseAbs().maxCoeff());
    const Eigen::Vector3d& a = points[i];
    const Eigen::Vector3d& b = points[(i + 1) % n];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  const double tol = 1e-12 * extent * extent;  // cross products below this count as zero
  if (!(std::abs(twice_area) > tol)) {
    fail(points_node, points_path +
                          ": the points enclose no area (they lie on one line); expected the "
                          "corners of a polygon with non-zero area");
  }

  // Edge i runs from point i to point i+1. Adjacent edges share a point, so only their folding
  // back onto each other counts; other pairs must not meet at all.
  const auto edge_name = [&](std::size_t i) {
    return "the edge from point " + std::to_string(i) + " to point " + std::to_string((i + 1) % n);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d &p = points[i], &q = points[(i + 1) % n];
    for (std::size_t j = i + 1; j < n; ++j) {
      const Eigen::Vector3d &r = points[j], &s = points[(j + 1) % n];
      bool meet = false;
      if (j == i + 1 || (i == 0 && j == n - 1)) {
        // The shared point is q == r (j == i + 1) or p == s (the closing edge); the edges fold
        // back when the third points lie on the same side along one line.
        const Eigen::Vector3d& shared = j == i + 1 ? q : p;
        const Eigen::Vector3d& a = j == i + 1 ? p : q;
        const Eigen::Vector3d& b = j == i + 1 ? s : r;
        meet = sign_of(cross2(shared, a, b), tol) == 0 && (a - shared).dot(b - shared) > 0.0;
      } else {
        meet = segments_meet(p, q, r, s, tol);
      }
      if (meet) {
        fail(points_node, points_path + ": " + edge_name(i) + " meets " + edge_name(j) +
                              "; expected a simple polygon (edges that do not cross or touch)");
      }
    }
  }
}

ShapeSpec ShapeReader::read_mesh(const YAML::Node& node, const std::string& path) const {
  expect_map(node, path, case_schema::all_keys("bodies[].shape.mesh"));
  ShapeSpec shape;
  shape.type = ShapeSpec::Type::Mesh;
  const YAML::Node file_node = require(node, path, "file");
  shape.file = text(file_node, child(path, "file"));
  expect(has_mesh_extension(shape.file), file_node, child(path, "file"),
         "a mesh file name ending in .stl, .obj, .off or .ply (any case)");
  if (auto v = find(node, "scale")) {
    const std::string scale_path = child(path, "scale");
    const std::string expected = "a number > 0 or a list of 3 numbers > 0 ([sx, sy, sz])";
    if (v->IsSequence()) {
      expect(v->size() == 3, *v, scale_path, expected);
      const std::vector<double> s = numbers(*v, scale_path, 3);
      expect(s[0] > 0.0 && s[1] > 0.0 && s[2] > 0.0, *v, scale_path, expected);
      shape.placement.scale = Eigen::Vector3d(s[0], s[1], s[2]);
    } else {
      const double s = number_if(
          *v, scale_path, [](double x) { return x > 0.0; }, expected);
      shape.placement.scale = Eigen::Vector3d::Constant(s);
    }
  }
  // Meshes are 3D whatever the case's dim, so rotate and translate always take 3 numbers.
  if (auto v = find(node, "rotate")) {
    const std::vector<double> r = numbers(*v, child(path, "rotate"), 3);
    shape.placement.rotate_deg = Eigen::Vector3d(r[0], r[1], r[2]);
  }
  if (auto v = find(node, "translate")) {
    const std::vector<double> t = numbers(*v, child(path, "translate"), 3);
    shape.placement.translate = Eigen::Vector3d(t[0], t[1], t[2]);
  }
  if (auto v = find(node, "repair")) shape.repair = boolean(*v, child(path, "repair"));
  const std::optional<YAML::Node> slice = find(node, "slice_y");
  if (dim() == 2) {
    if (!slice) {
      fail(node, "missing required key '" + child(path, "slice_y") +
                     "': a 2D case cuts the placed mesh by the plane y = slice_y and uses the "
                     "section, its (x, z) becoming the 2D (x, y)");
    }
    shape.slice_y = number(*slice, child(path, "slice_y"));
  } else if (slice) {
    fail(*slice, child(path, "slice_y") +
                     ": only 2D cases cut a mesh by a plane; a 3D case uses the whole mesh, so "
                     "leave slice_y out");
  }
  return shape;
}

ShapeSpec ShapeReader::read_csg(ShapeSpec::Type type, const YAML::Node& node,
                                const std::string& path) const {
  const bool is_union = type == ShapeSpec::Type::Union;
  expect(node.IsSequence() && node.size() >= 2, node, path,
         is_union ? "a list of at least 2 shapes"
                  : "a list of at least 2 shapes (the first minus all the others)");
  ShapeSpec shape;
  shape.type = type;
  for (std::size_t i = 0; i < node.size(); ++i) {
    shape.children.push_back(read(node[i], item(path, i)));
  }
  return shape;
}

}  // namespace

ShapeSpec read_shape(const NodeReader& reader, const YAML::Node& node, const std::string& path) {
  return ShapeReader(reader).read(node, path);
}

}  // namespace swell::case_parse
