// MeshSolid: a closed triangle mesh read with CGAL, checked (closed, no self-intersections,
// outward normals), optionally repaired, and queried through one prebuilt AABB tree.
//
// Thread safety: after load() the mesh, the AABB tree (with its distance-query KD-tree) and
// the Side_of_triangle_mesh functor are never modified, so contains(), signed_distance(),
// bounds(), volume() and slice_y() may be called concurrently from OpenMP threads.
#include "geometry/mesh_solid.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Polygon_mesh_slicer.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <new>
#include <sstream>
#include <stdexcept>

#include "geometry/lattice_fill.hpp"

namespace swell::geometry {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Traits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;
using Inside = CGAL::Side_of_triangle_mesh<Mesh, K>;
using face_descriptor = Mesh::Face_index;
using halfedge_descriptor = Mesh::Halfedge_index;

// Bounds of `repair: true`'s self-intersection removal (docs/user-guide/case-files.md#shapes).
constexpr std::size_t kMaxRepairFaces = 200000;
constexpr std::size_t kMaxRepairPairs = 5000;
constexpr double kMinRepairEdge = 1e-7;  // shortest edge / mesh size (float STL: ~6e-8)

constexpr const char* kFormats = ".stl (ASCII or binary), .obj, .off, .ply";

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Reads the file as a polygon soup, dispatching on the (case-insensitive) extension.
void read_soup(const std::string& path, std::vector<Point>& points,
               std::vector<std::vector<std::size_t>>& polygons) {
  const std::string ext = lower_extension(path);
  if (ext != ".stl" && ext != ".obj" && ext != ".off" && ext != ".ply") {
    throw MeshError(path + ": unknown mesh format '" + ext + "'; supported formats: " + kFormats);
  }
  if (!std::ifstream(path, std::ios::binary)) {
    throw MeshError(path + ": cannot open the mesh file (supported formats: " + kFormats + ")");
  }
  bool ok = false;
  // The readers report problems on std::cerr only with verbose(true); we keep them quiet and
  // throw one message instead.
  if (ext == ".stl") {
    ok = CGAL::IO::read_STL(path, points, polygons);
  } else if (ext == ".obj") {
    ok = CGAL::IO::read_OBJ(path, points, polygons);
  } else if (ext == ".off") {
    ok = CGAL::IO::read_OFF(path, points, polygons);
  } else {
    ok = CGAL::IO::read_PLY(path, points, polygons);
  }
  if (!ok) {
    throw MeshError(
        path + ": cannot read the mesh as " + ext +
        " (the file is malformed or not in that format; supported formats: " + kFormats + ")");
  }
  if (polygons.empty()) throw MeshError(path + ": the mesh has no faces");
}

// Scale, then rotate about x, then y, then z (degrees), then translate.
Eigen::Affine3d placement_transform(const Placement& pl) {
  constexpr double deg = 3.14159265358979323846 / 180.0;
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(pl.rotate_deg.z() * deg, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(pl.rotate_deg.y() * deg, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(pl.rotate_deg.x() * deg, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  t.linear() = r * pl.scale.asDiagonal();
  t.translation() = pl.translate;
  return t;
}

Point to_point(const Eigen::Vector3d& p) {
  return Point(p.x(), p.y(), p.z());
}

std::vector<halfedge_descriptor> border_cycles(const Mesh& mesh) {
  std::vector<halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  return cycles;
}

std::size_t count_border_edges(const Mesh& mesh) {
  std::size_t n = 0;
  for (halfedge_descriptor h : mesh.halfedges())
    if (mesh.is_border(h)) ++n;
  return n;
}

std::size_t count_self_intersections(const Mesh& mesh) {
  std::vector<std::pair<face_descriptor, face_descriptor>> pairs;
  PMP::self_intersections(faces(mesh), mesh, std::back_inserter(pairs));
  return pairs.size();
}

// The cyclic vertex order of each face, rotated to start at its smallest vertex index, so a
// reorientation shows up as a changed triple.
std::vector<std::array<std::uint32_t, 3>> face_orders(const Mesh& mesh) {
  std::vector<std::array<std::uint32_t, 3>> out;
  out.reserve(mesh.number_of_faces());
  for (face_descriptor f : mesh.faces()) {
    std::array<std::uint32_t, 3> v{};
    int i = 0;
    for (auto vd : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) v[i++ % 3] = vd.idx();
    std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
    out.push_back(v);
  }
  return out;
}

// Closest-point search on the AABB tree that starts from a bound on the squared distance,
// visits the nearer child box first and prunes boxes farther than the best distance so far.
// CGAL's own closest_point() visits children in a fixed order; the nearer-first order and a
// tight starting bound (max_distance^2 for capped queries) cut the faces visited.
class BoundedDistanceTraits {
 public:
  using Priority = double;
  using Node = CGAL::AABB_node<Traits>;

  BoundedDistanceTraits(const Traits& traits, double bound_sq)
      : traits_(traits), best_sq_(bound_sq) {}

  bool go_further() const { return true; }
  void intersection(const Point& q, const Primitive& pr) {
    const double d =
        CGAL::squared_distance(q, CGAL::internal::Primitive_helper<Traits>::get_datum(pr, traits_));
    if (d < best_sq_) best_sq_ = d;
  }
  bool do_intersect(const Point& q, const Node& node) const {
    return box_squared_distance(q, node.bbox()) < best_sq_;
  }
  std::pair<bool, Priority> do_intersect_with_priority(const Point& q, const Node& node) const {
    const double d = box_squared_distance(q, node.bbox());
    return {d < best_sq_, -d};  // higher priority is visited first
  }
  double best_squared_distance() const { return best_sq_; }

 private:
  static double box_squared_distance(const Point& q, const CGAL::Bbox_3& b) {
    double s = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double e = std::max({b.min(d) - q[d], 0.0, q[d] - b.max(d)});
      s += e * e;
    }
    return s;
  }

  const Traits& traits_;
  double best_sq_;
};

// Closes the mesh or throws; with repair, stitches borders and fills each remaining hole.
void make_closed(Mesh& mesh, const std::string& path, bool repair, MeshReport& rep) {
  rep.border_edges = count_border_edges(mesh);
  if (rep.border_edges == 0) return;
  const std::size_t holes = border_cycles(mesh).size();
  if (!repair) {
    throw MeshError(path + ": the mesh is not closed: " +
                    plural(rep.border_edges, "border edge", "border edges") + " around " +
                    plural(holes, "hole", "holes") + "; set `repair: true` to fill them");
  }
  if (const std::size_t stitched = PMP::stitch_borders(mesh); stitched > 0) {
    rep.repairs.push_back("stitched " + plural(stitched, "pair", "pairs") +
                          " of coincident border edges");
  }
  const std::vector<halfedge_descriptor> cycles = border_cycles(mesh);
  std::size_t faces_added = 0, vertices_added = 0;
  for (halfedge_descriptor h : cycles) {
    std::vector<face_descriptor> new_faces;
    std::vector<Mesh::Vertex_index> new_vertices;
    PMP::triangulate_and_refine_hole(mesh, h, std::back_inserter(new_faces),
                                     std::back_inserter(new_vertices));
    faces_added += new_faces.size();
    vertices_added += new_vertices.size();
  }
  if (!cycles.empty()) {
    rep.repairs.push_back("filled " + plural(cycles.size(), "hole", "holes") + " (" +
                          plural(faces_added, "face", "faces") + ", " +
                          plural(vertices_added, "vertex", "vertices") + " added)");
  }
  if (const std::size_t left = count_border_edges(mesh); left > 0) {
    throw MeshError(path + ": the mesh is still not closed after repair: " +
                    plural(left, "border edge", "border edges") + " around " +
                    plural(border_cycles(mesh).size(), "hole", "holes") +
                    " could not be filled; close the mesh in a mesh editor");
  }
}

// Removes self-intersections or throws; with repair, runs CGAL's (experimental) removal.
void make_free_of_self_intersections(Mesh& mesh, const std::string& path, bool repair,
                                     MeshReport& rep) {
  rep.self_intersections = count_self_intersections(mesh);
  if (rep.self_intersections == 0) return;
  const std::string pairs = plural(rep.self_intersections, "pair", "pairs");
  if (!repair) {
    throw MeshError(path + ": " + pairs +
                    " of faces intersect; set `repair: true` to try CGAL's self-intersection "
                    "removal");
  }
  // Edges far below float precision of the mesh's size (slivers, denormal coordinates) make
  // the autorefinement dereference freed triangulation faces (SIGSEGV, found by fuzzing):
  // refused before it runs.
  {
    CGAL::Bbox_3 box;
    for (auto v : mesh.vertices()) box += mesh.point(v).bbox();
    const double size =
        std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                  CGAL::square(box.zmax() - box.zmin()));
    double shortest = std::numeric_limits<double>::infinity();
    for (auto e : mesh.edges())
      shortest = std::min(
          shortest, std::sqrt(CGAL::squared_distance(mesh.point(mesh.source(mesh.halfedge(e))),
                                                     mesh.point(mesh.target(mesh.halfedge(e))))));
    if (!(shortest >= kMinRepairEdge * size)) {
      std::ostringstream m;
      m << path << ": " << pairs << " of faces intersect, and the mesh has an edge of " << shortest
        << " m, under " << kMinRepairEdge << " of its size (" << size
        << " m): `repair: true` cannot remove self-intersections among such slivers; fix the "
           "mesh in a mesh editor";
      throw MeshError(m.str());
    }
  }
  // CGAL's removal is experimental and its cost grows fast with the faces involved; beyond
  // these bounds it is refused rather than left to run for hours.
  if (mesh.number_of_faces() > kMaxRepairFaces || rep.self_intersections > kMaxRepairPairs) {
    throw MeshError(path + ": " + pairs + " of faces intersect in a mesh of " +
                    plural(mesh.number_of_faces(), "face", "faces") +
                    "; `repair: true` removes self-intersections only in meshes of at most " +
                    std::to_string(kMaxRepairFaces) + " faces with at most " +
                    std::to_string(kMaxRepairPairs) +
                    " intersecting pairs; fix the mesh in a mesh editor");
  }
  // First CGAL's local removal (smoothing or re-filling small patches: meshing defects); if
  // that fails, autorefinement, which cuts the faces along their intersections and drops the
  // parts inside the solid (overlapping closed parts become their union).
  // CGAL gives up on some configurations by throwing (autorefinement: "Non-handled triple
  // intersection of input triangles", found by fuzzing): a mesh error like the others.
  const Mesh original = mesh;
  const char* how = "local removal";
  bool fixed = false;
  try {
    fixed = PMP::experimental::remove_self_intersections(mesh);
    mesh.collect_garbage();
    fixed = fixed && CGAL::is_closed(mesh) && count_self_intersections(mesh) == 0;
    if (!fixed) {
      mesh = original;
      how = "autorefinement";
      fixed = PMP::experimental::autorefine_and_remove_self_intersections(mesh);
      mesh.collect_garbage();
    }
  } catch (const std::exception& e) {
    throw MeshError(path + ": " + pairs + " of faces intersect and CGAL's self-intersection " +
                    "removal (" + how + ") gave up: " + e.what() +
                    "; fix the mesh in a mesh editor (e.g. a boolean union of the overlapping "
                    "parts)");
  }
  const std::size_t left = count_self_intersections(mesh);
  const bool closed = CGAL::is_closed(mesh);
  if (!fixed || left > 0 || !closed) {
    throw MeshError(path + ": " + pairs +
                    " of faces intersect and CGAL's self-intersection removal could not fix "
                    "them (" +
                    (left > 0 ? plural(left, "pair", "pairs") + " left"
                              : std::string(closed ? "some remain" : "the result is open")) +
                    "); fix the mesh in a mesh editor (e.g. a boolean union of the overlapping "
                    "parts)");
  }
  rep.repairs.push_back("removed self-intersections (" + pairs + " of faces, by " + how + ")");
}

// Orients every component so the mesh bounds its volume with outward normals.
void orient_outward(Mesh& mesh, MeshReport& rep) {
  auto fccmap = mesh.add_property_map<face_descriptor, std::size_t>("f:swell_cc").first;
  const std::size_t components = PMP::connected_components(mesh, fccmap);
  mesh.remove_property_map(fccmap);
  if (components == 1) {
    if (!PMP::is_outward_oriented(mesh)) {
      PMP::reverse_face_orientations(mesh);
      rep.reoriented = true;
    }
    return;
  }
  // Several shells (e.g. a hollow body): orient each by its nesting level.
  const auto before = face_orders(mesh);
  PMP::orient_to_bound_a_volume(mesh);
  rep.reoriented = face_orders(mesh) != before;
}

}  // namespace

struct MeshSolid::Impl {
  Mesh mesh;
  Tree tree;
  std::unique_ptr<Inside> inside;  // built on `tree`, which must not move afterwards
  MeshReport report;
  Aabb box;
  double volume = 0.0;
  std::string name;  // file name without folders, for describe()
};

// Any other exception out of CGAL (a precondition or an unhandled configuration) is a mesh
// error too: the file is named, and a run stops with exit 2 instead of an internal error.
std::shared_ptr<MeshSolid> MeshSolid::load(const std::string& path, const Placement& placement,
                                           bool repair, MeshReport* report) try {
  auto impl = std::make_unique<Impl>();
  MeshReport& rep = impl->report;
  rep.file = path;
  impl->name = std::filesystem::path(path).filename().string();

  for (int d = 0; d < 3; ++d) {
    if (!std::isfinite(placement.scale[d]) || placement.scale[d] == 0.0) {
      throw MeshError(path + ": the placement scale must be finite and non-zero on every axis");
    }
  }

  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  read_soup(path, points, polygons);
  // CGAL's exact predicates and repairs assume sane numbers: non-finite or huge coordinates
  // make them crash (SIGFPE in GMP) or run without end, so they are refused here.
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& q = points[i];
    if (!std::isfinite(q.x()) || !std::isfinite(q.y()) || !std::isfinite(q.z())) {
      std::ostringstream m;
      m << path << ": vertex " << i << " has a non-finite coordinate (" << q.x() << ", " << q.y()
        << ", " << q.z() << "); the file is corrupt";
      throw MeshError(m.str());
    }
  }
  for (const auto& poly : polygons)
    for (const std::size_t v : poly)
      if (v >= points.size())
        throw MeshError(path + ": a face refers to vertex " + std::to_string(v) + " of " +
                        std::to_string(points.size()));

  // Merges duplicate points and polygons, drops degenerate polygons and isolated points; it
  // never changes the shape, so it always runs.
  const std::size_t points_in = points.size(), polygons_in = polygons.size();
  PMP::repair_polygon_soup(points, polygons);
  if (repair && (points.size() != points_in || polygons.size() != polygons_in)) {
    rep.repairs.push_back("cleaned the polygon soup: " + std::to_string(points_in) + " -> " +
                          std::to_string(points.size()) + " vertices, " +
                          std::to_string(polygons_in) + " -> " + std::to_string(polygons.size()) +
                          " faces");
  }
  if (polygons.empty()) throw MeshError(path + ": the mesh has no valid faces");

  const Eigen::Affine3d t = placement_transform(placement);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d x = t * Eigen::Vector3d(points[i].x(), points[i].y(), points[i].z());
    if (!(x.cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      std::ostringstream m;
      m << path << ": vertex " << i << " lies at (" << x.x() << ", " << x.y() << ", " << x.z()
        << ") m after placement, beyond the +-" << kMaxCoordinate
        << " m that geometry may reach (check the units and `scale`)";
      throw MeshError(m.str());
    }
    points[i] = to_point(x);
  }

  // A mesh smaller than a micrometre is no geometry (and CGAL's arithmetic underflows on it).
  {
    Aabb b;
    for (const Point& q : points) b.extend(Eigen::Vector3d(q.x(), q.y(), q.z()));
    const double size = (b.max - b.min).norm();
    if (!(size >= 1e-6)) {
      std::ostringstream m;
      m << path << ": the mesh spans only " << size
        << " m after placement (at least 1e-6 m expected; check `scale`)";
      throw MeshError(m.str());
    }
  }
  // Makes neighbouring faces agree on orientation; duplicates vertices where the soup is not
  // manifold (such a mesh then shows up as not closed).
  PMP::orient_polygon_soup(points, polygons);
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    throw MeshError(path +
                    ": the faces cannot be joined into a consistent surface "
                    "(non-manifold or non-orientable)");
  }
  Mesh& mesh = impl->mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (!CGAL::is_triangle_mesh(mesh)) PMP::triangulate_faces(mesh);

  make_closed(mesh, path, repair, rep);
  make_free_of_self_intersections(mesh, path, repair, rep);
  orient_outward(mesh, rep);
  mesh.collect_garbage();

  rep.closed = CGAL::is_closed(mesh);
  rep.vertices = mesh.number_of_vertices();
  rep.faces = mesh.number_of_faces();
  impl->volume = PMP::volume(mesh);
  rep.volume = impl->volume;
  for (auto v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    impl->box.extend(Eigen::Vector3d(p.x(), p.y(), p.z()));
  }

  // Build everything the queries use now, so that they are read-only afterwards.
  impl->tree.insert(faces(mesh).first, faces(mesh).second, mesh);
  impl->tree.build();
  impl->tree.accelerate_distance_queries();
  impl->inside = std::make_unique<Inside>(impl->tree);

  if (report) *report = rep;
  return std::shared_ptr<MeshSolid>(new MeshSolid(std::move(impl)));
} catch (const MeshError&) {
  throw;
} catch (const std::bad_alloc&) {
  throw;
} catch (const std::exception& e) {
  throw MeshError(path + ": CGAL could not process this mesh (" + e.what() +
                  "); check it in a mesh editor");
}

MeshSolid::MeshSolid(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MeshSolid::~MeshSolid() = default;

bool MeshSolid::contains(const Eigen::Vector3d& p) const {
  // Points on the surface count as inside.
  return (*impl_->inside)(to_point(p)) != CGAL::ON_UNBOUNDED_SIDE;
}

double MeshSolid::signed_distance(const Eigen::Vector3d& p) const {
  const Point q = to_point(p);
  // The KD-tree hint (nearest face reference point) bounds the distance from above.
  const double bound = CGAL::squared_distance(q, impl_->tree.best_hint(q).first);
  BoundedDistanceTraits search(impl_->tree.traits(), bound);
  impl_->tree.traversal_with_priority(q, search);
  const double d = std::sqrt(search.best_squared_distance());
  return contains(p) ? -d : d;
}

double MeshSolid::signed_distance_within(const Eigen::Vector3d& p, double max_distance) const {
  const Point q = to_point(p);
  BoundedDistanceTraits search(impl_->tree.traits(), max_distance * max_distance);
  impl_->tree.traversal_with_priority(q, search);
  const double d = std::min(std::sqrt(search.best_squared_distance()), max_distance);
  return contains(p) ? -d : d;
}

Eigen::Vector3d MeshSolid::closest_surface_point(const Eigen::Vector3d& p) const {
  const Point x = impl_->tree.closest_point(to_point(p));
  return {x.x(), x.y(), x.z()};
}

double MeshSolid::signed_distance_cgal(const Eigen::Vector3d& p) const {
  const double d = std::sqrt(impl_->tree.squared_distance(to_point(p)));
  return contains(p) ? -d : d;
}

Aabb MeshSolid::bounds() const {
  return impl_->box;
}

double MeshSolid::volume() const {
  return impl_->volume;
}

std::string MeshSolid::describe() const {
  return "mesh " + impl_->name + " (" + plural(impl_->report.faces, "face", "faces") + ")";
}

std::vector<std::vector<Eigen::Vector2d>> MeshSolid::slice_y(double y0) const {
  std::vector<std::vector<Eigen::Vector2d>> loops;
  if (y0 < impl_->box.min.y() || y0 > impl_->box.max.y()) return loops;
  CGAL::Polygon_mesh_slicer<Mesh, K> slicer(impl_->mesh);
  std::vector<std::vector<Point>> polylines;
  slicer(K::Plane_3(0.0, 1.0, 0.0, -y0), std::back_inserter(polylines));
  for (const auto& line : polylines) {
    std::vector<Eigen::Vector2d> loop;
    loop.reserve(line.size());
    for (const Point& p : line) loop.emplace_back(p.x(), p.z());
    // Closed polylines repeat their first point at the end; the loop does not.
    if (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
    // On a closed mesh an open piece only comes from a degenerate cut (the plane through a
    // vertex or along an edge); with 3 points or more it is closed as a loop, shorter ones
    // have no area.
    if (loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

const MeshReport& MeshSolid::report() const {
  return impl_->report;
}

}  // namespace swell::geometry
