// `swell fill CASE.yaml -o DIR`: builds the particles exactly as `swell run` does (setup_case),
// writes them to DIR/<name>_fill.vtp and prints what the fill did: particles per body, the
// lattice volume check of each fluid body, the meshes read (faces, orientation, repairs) and
// the time taken. For checking a geometry before running it.
#pragma once

#include <cmath>
#include <iosfwd>
#include <string>
#include <vector>

#include "apps/subcommand.hpp"
#include "case/spec.hpp"
#include "geometry/lattice_fill.hpp"
#include "geometry/mesh_solid.hpp"

namespace swell {

struct FillCommandOptions {
  std::string out_dir;  // default: out/<case name>
  int threads = 0;      // 0: OpenMP default
};

// The volume check of one fluid body: its particles against the water its region holds once
// the structures are cut out. Volumes are areas in 2D.
struct FluidVolumeCheck {
  std::string body;
  double particles = 0.0;   // fluid particles x dp^D
  double lattice = 0.0;     // lattice points of the region x dp^D, before any cut
  double region = 0.0;      // exact region volume, NaN if unknown
  double structures = 0.0;  // the structures' part of the region (counted, see spacing)
  double spacing = 0.0;     // of the lattice that counted it; 0: no structure in the region
  double water() const { return region - structures; }  // what the particles should fill
  // Staircase and wall gaps; exactly 0 when the difference is only rounding.
  double void_volume() const {
    const double v = water() - particles;
    return std::abs(v) <= 1e-12 * std::abs(water()) ? 0.0 : v;
  }
};

struct FillSummary {
  std::size_t fluid = 0, boundary = 0;
  std::string vtp;   // the file written
  std::string info;  // fill_info.yaml beside it: counts, volume check, provenance
  double fill_seconds = 0.0;
  std::vector<FluidVolumeCheck> volumes;  // per fluid body, case order
};

FillSummary run_fill(const CaseSpec& spec, const FillCommandOptions& opt, std::ostream& log);

// The report printed by `swell fill` (one line per mesh and per body, then the totals); with
// `volumes`, each fluid body's volume check against its region less the structures.
void print_fill_report(std::ostream& out, const std::vector<geometry::BodyFillReport>& bodies,
                       const std::vector<geometry::MeshReport>& meshes, int dim, double dp,
                       double fill_seconds, const std::vector<FluidVolumeCheck>* volumes = nullptr);

// Adds `swell fill` to `app`.
Subcommand add_fill_command(CLI::App& app);

}  // namespace swell
