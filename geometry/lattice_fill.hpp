// Turns body descriptions into particle positions on one global lattice.
//
// Every body samples the same lattice, points at (i + 1/2) dp on each axis, so fluid and wall
// particles of different bodies line up and never overlap. A box face placed on a multiple of
// dp then lies half-way between two lattice planes: the fluid fills its volume exactly
// (N dp^D = V) and the first wall layer sits dp/2 behind the surface.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/shapes.hpp"

namespace swell::geometry {

struct BodyGeometry {
  std::string name;
  bool fluid = true;
  Box box;
  bool walls_inside = true;  // boundary: fluid inside the shape (tank) or outside (structure)
  int layers = 3;
  std::vector<std::string> open;  // faces left open: xmin, xmax, ymin, ymax, zmin, zmax
};

struct FilledBody {
  std::string name;
  bool fluid = true;
  std::vector<Eigen::Vector3d> points;  // z = 0 in 2D
};

struct FillOptions {
  int dim = 2;
  double dp = 0.0;
  // Fluid points closer than this to a wall body's surface are dropped (default dp/2, which
  // on an aligned lattice keeps every fluid point whose cell lies inside the fluid region).
  double gap_factor = 0.5;
};

// Fills every body; fluid bodies lose the points inside walls and points of earlier fluid
// bodies. Throws std::invalid_argument naming the body if one gets no particle.
std::vector<FilledBody> fill_bodies(const std::vector<BodyGeometry>& bodies,
                                    const FillOptions& opt);

}  // namespace swell::geometry
