// From a parsed case to a finished run: particles and parameters (setup_case), then the time
// loop with VTK output, diagnostics, a progress line and a summary (run_case). Used by the
// `swell` command and by the end-to-end tests.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "geometry/lattice_fill.hpp"
#include "geometry/mesh_solid.hpp"
#include "io/case_spec.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/time/simulation.hpp"
#include "bc/dbc.hpp"
#include "bc/motion.hpp"
#include "solver/solver_params.hpp"

namespace swell {

struct BodyCount {
  std::string name;
  bool fluid = true;
  std::size_t particles = 0;
};

template <int D>
struct CaseSetup {
  SolverParams params;
  ParticleSet<D> particles;
  std::vector<BodyCount> bodies;
  double hswl = 0.0;   // still-water height used for c0
  double floor = 0.0;  // lowest fluid level along "up", for the surge front
  // What the fill did, for the run summary and `swell fill`: per body (case order) counts and
  // the lattice volume check, every mesh loaded (faces, orientation, repairs), and the time
  // spent building shapes and filling the lattice.
  std::vector<MotionLaw> motions;  // per body (index = body id); none for fluid and fixed walls
  std::vector<geometry::BodyFillReport> fill;
  std::vector<geometry::MeshReport> meshes;
  double fill_seconds = 0.0;
};

// Builds the particles (geometry/), hydrostatic densities (bc/) and solver parameters. Mesh
// files are read relative to the case file's folder. Throws CaseError (file and line) for a
// shape that cannot be built or a body that cannot be filled.
template <int D>
CaseSetup<D> setup_case(const CaseSpec& spec);

// The simulation of a set-up case: DBC walls and, if a body moves, the motion hook. `particles`
// are the setup's (fresh start) or a checkpoint's (restart).
template <int D>
Simulation<D> make_simulation(const CaseSetup<D>& setup, ParticleSet<D> particles);

struct RunOptions {
  std::string out_dir;          // default: out/<case name>
  int threads = 0;              // 0: OpenMP default
  bool progress = true;         // progress line on stderr
  std::ostream* log = nullptr;  // summary stream (stdout if null)
  // Continue from OUTDIR/checkpoint.h5 (or its .prev if the last one is damaged) up to the
  // case's time.end; outputs written after the checkpoint time are replaced.
  bool restart = false;
};

struct RunSummary {
  std::size_t fluid = 0, boundary = 0;
  long steps = 0;
  double sim_time = 0.0;
  double wall_seconds = 0.0;
  double particle_steps_per_second = 0.0;
  ExclusionCounts excluded;
  PhaseTimes phases;
  double output_seconds = 0.0;
  int snapshots = 0;
  double restarted_from = -1.0;  // checkpoint time when restarted
};

// Runs the case to time.end, writing OUTDIR/<name>.pvd + OUTDIR/vtk/*.vtp, OUTDIR/<name>.h5
// (snapshots + metadata), OUTDIR/checkpoint.h5, OUTDIR/gauges_<kind>.csv and
// OUTDIR/diagnostics.csv. Throws InstabilityError if the run blows up (the last checkpoint
// written before stays valid).
RunSummary run_case(const CaseSpec& spec, const RunOptions& options);

}  // namespace swell
