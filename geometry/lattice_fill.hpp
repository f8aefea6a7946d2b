// Turns body descriptions into particle positions on one global lattice.
//
// Every body samples the same lattice, points at (i + 1/2) dp on each axis, so fluid and wall
// particles of different bodies line up and never overlap. A box face placed on a multiple of
// dp then lies half-way between two lattice planes: the fluid fills its volume exactly
// (N dp^D = V) and the first wall layer sits dp/2 behind the surface.
//
// Bodies are Shapes (geometry/shape.hpp). Wall particles are the lattice points within
// `layers` dp of the surface on the solid side; fluid particles the points of the fluid
// region clear of every wall by the gap and not taken by an earlier fluid body.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/shape.hpp"

namespace swell::geometry {

struct BodyGeometry {
  std::string name;
  bool fluid = true;
  ShapePtr shape;            // null only for a fluid body given by fill_below
  bool walls_inside = true;  // boundary: fluid inside the shape (tank) or outside (structure)
  int layers = 3;
  // Boundary, walls inside: faces left without wall, any of xmin, xmax, ymin, ymax, zmin,
  // zmax. A wall point beyond the shape's bounds on that side is dropped.
  std::vector<std::string> open;
  // Fluid, instead of `shape`: every point below `fill_below` along the vertical axis (y in
  // 2D, z in 3D) inside the shape of body `container`, a boundary body with walls inside.
  std::optional<double> fill_below;
  int container = -1;
};

// What the fill did with one body, for the setup report.
struct BodyFillReport {
  std::string name;
  bool fluid = true;
  std::string region;  // Shape::describe(), or "below y = L inside 'tank'"
  std::size_t particles = 0;
  // Fluid: lattice points of the body's region before the points near walls or taken by an
  // earlier fluid body were removed, and the exact region volume (area in 2D), NaN if unknown.
  std::size_t in_region = 0;
  double region_volume = std::numeric_limits<double>::quiet_NaN();

  // in_region dp^D relative to region_volume, minus 1; NaN when the volume is unknown.
  double volume_error(int dim, double dp) const;
};

struct FilledBody {
  BodyFillReport report;
  std::vector<Eigen::Vector3d> points;  // z = 0 in 2D
  // With FillOptions::share: per lattice row of the body (rows in lattice order, the same rows
  // whatever the share), how many of `points` lie in the row and how many of those are the
  // share's own (FillShare::owns); a row's own points are consecutive. Report counts (in_region,
  // particles) then count own points only.
  std::vector<std::uint32_t> row_points, row_owned;
};

// A share of the lattice, for a set-up distributed over processes (issue #16): the points
// whose coordinate along `axis` lies in [lo, hi) are the share's own; those within `margin`
// outside it are filled too (a neighbour's own points, which the set-up reads near the share's
// faces). Shares that tile the axis own every point exactly once.
struct FillShare {
  int axis = 0;
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  double margin = 0.0;
  bool owns(const Eigen::Vector3d& p) const { return p[axis] >= lo && p[axis] < hi; }
  bool reaches(double x) const { return x >= lo - margin && x < hi + margin; }
};

struct FillOptions {
  int dim = 2;
  double dp = 0.0;
  // Fluid points closer than this to a wall body's surface are dropped (default dp/2, which
  // on an aligned lattice keeps every fluid point whose cell lies inside the fluid region).
  double gap_factor = 0.5;
  // Points within this fraction of dp short of the gap still count as clear: aligned geometry
  // puts them exactly dp/2 from the surface, and single-precision STL coordinates (relative
  // error 6e-8) must not cost a whole layer of fluid.
  double gap_tolerance = 1e-3;
  // Reuse a shape test for the next points of a row while the signed distance (1-Lipschitz)
  // cannot cross a threshold there. Same result as evaluating every point; off for tests.
  bool march = true;
  // Fill only this share of the lattice (none: all of it). A body may then get no point here
  // (no error: the caller checks the sum over the shares).
  std::optional<FillShare> share;
};

// An upper estimate of the particles fill_bodies() would make, per body (case order), from the
// bounds alone (no shape test, instant for any dp): lattice points in the bounding box of a
// fluid region, and of a wall region (the shape's bounds plus the wall thickness) less the
// points inside the shape where its volume is known. Throws std::invalid_argument naming the
// body if its bounds are not finite or reach beyond kMaxCoordinate (geometry/shape.hpp).
struct FillEstimate {
  std::vector<double> particles;  // per body
  double total = 0.0;
};
FillEstimate estimate_fill(const std::vector<BodyGeometry>& bodies, const FillOptions& opt);

// Fills every body, in parallel over lattice rows (OpenMP); the points come out in lattice
// order (z, then y, then x) whatever the thread count. A fluid point is kept when it lies in
// the body's region and, for every boundary body: with walls inside, at depth >= gap inside
// its shape (unless it lies beyond the body's walls, more than layers dp + gap outside its
// bounds); with walls outside, at distance >= gap outside its shape; and no earlier fluid body
// holds it. Throws std::invalid_argument naming the body if one gets no particle or is
// inconsistent (missing shape, bad container).
std::vector<FilledBody> fill_bodies(const std::vector<BodyGeometry>& bodies,
                                    const FillOptions& opt);

}  // namespace swell::geometry
