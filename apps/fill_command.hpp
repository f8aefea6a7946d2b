// `swell fill CASE.yaml -o DIR`: builds the particles exactly as `swell run` does (setup_case),
// writes them to DIR/<name>_fill.vtp and prints what the fill did: particles per body, the
// lattice volume check of each fluid body, the meshes read (faces, orientation, repairs) and
// the time taken. For checking a geometry before running it.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "geometry/lattice_fill.hpp"
#include "geometry/mesh_solid.hpp"
#include "io/case_spec.hpp"

namespace swell {

struct FillCommandOptions {
  std::string out_dir;  // default: out/<case name>
  int threads = 0;      // 0: OpenMP default
};

struct FillSummary {
  std::size_t fluid = 0, boundary = 0;
  std::string vtp;  // the file written
  double fill_seconds = 0.0;
};

FillSummary run_fill(const CaseSpec& spec, const FillCommandOptions& opt, std::ostream& log);

// The report printed by `swell fill` (one line per mesh and per body, then the totals).
void print_fill_report(std::ostream& out, const std::vector<geometry::BodyFillReport>& bodies,
                       const std::vector<geometry::MeshReport>& meshes, int dim, double dp,
                       double fill_seconds);

}  // namespace swell
