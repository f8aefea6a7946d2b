// The fluid volume check of `swell fill`: how much of a fluid body's region the structures
// (boundary bodies with walls outside: beaches, caissons, rocks) take, so that the fluid's
// N dp^D is compared with the volume the water really has, region less structures.
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/lattice_fill.hpp"

namespace swell::geometry {

struct StructureOverlap {
  double volume = 0.0;   // of region and structures together (area in 2D) [m^D]
  double spacing = 0.0;  // of the counting lattice [m]; 0 when no structure reaches the region
  std::size_t points = 0;
};

// Volume of the intersection of body `fluid`'s region (its shape, or its container below the
// fill level) with the union of the structures, by counting the points of a lattice of
// spacing dp / refine (points at (i + 1/2) spacing, so faces on multiples of dp are counted
// exactly) over the part of the region's bounds that the structures' bounds cover. The error
// is below (structure surface inside the region) x spacing. `refine` is lowered, if needed, to
// keep the count under `max_points`. Throws std::invalid_argument for a body that is not a
// fluid body or an index out of range.
StructureOverlap structures_in_region(const std::vector<BodyGeometry>& bodies, std::size_t fluid,
                                      int dim, double dp, int refine, double max_points = 4e7);

}  // namespace swell::geometry
