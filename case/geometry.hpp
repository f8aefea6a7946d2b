// From a case's bodies (CaseSpec) to the bodies the lattice fill takes (geometry::BodyGeometry):
// the one translation shared by `swell run`, `swell fill` (setup_case) and `swell foam`.
#pragma once

#include <vector>

#include "case/spec.hpp"
#include "geometry/lattice_fill.hpp"
#include "geometry/mesh_solid.hpp"

namespace swell {

// One BodyGeometry per body, in case order: every shape built (mesh files read relative to the
// case file's folder; each mesh read appends its MeshReport to `meshes`, if given), and every
// `fill: {below, inside}` given as its level and its container's index (BodySpec::fill_container,
// resolved and checked when the case file was read). Throws CaseError (file, line, key path) for
// a shape that cannot be built.
std::vector<geometry::BodyGeometry> case_geometry(
    const CaseSpec& spec, std::vector<geometry::MeshReport>* meshes = nullptr);

}  // namespace swell
