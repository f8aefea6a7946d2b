// From a parsed case to what a run starts from: the particles (geometry/ fill), hydrostatic
// densities (bc/) and solver parameters (setup_case), then the simulation with its wall model
// and motion hook (make_simulation). Shared by `swell run`, `swell fill`, `swell bench` and the
// lean benchmark runner (bench/), which must not depend on apps/.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bc/damping.hpp"
#include "bc/motion.hpp"
#include "case/spec.hpp"
#include "geometry/lattice_fill.hpp"
#include "geometry/mesh_solid.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/time/simulation.hpp"

namespace swell {

// How a set-up distributed over the ranks of a decomposed run (issue #16) combines what each
// rank filled. The default is one process, where every call is the identity: `swell fill`,
// `swell bench` and one-rank runs. run/ passes one over parallel::Comm (case/ does not link
// the MPI build). Every rank makes the same calls in the same order.
struct SetupReduce {
  virtual ~SetupReduce() = default;
  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }
  virtual int node_size() const { return 1; }  // ranks sharing this machine's memory
  virtual void sum(std::vector<double>& v) const { (void)v; }
  virtual void sum(std::vector<std::uint64_t>& v) const { (void)v; }
  virtual void max(std::vector<double>& v) const { (void)v; }
  // Element-wise sums over the lower ranks (rank 0: zeros).
  virtual void exscan(std::vector<std::uint64_t>& v) const { v.assign(v.size(), 0); }
  // The lowest rank's non-empty message, on every rank ("": none failed).
  virtual std::string first_message(const std::string& mine) const { return mine; }
};

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
  // Damping zones (case order) and the settling phase, for the hooks of bc/damping.hpp.
  std::vector<DampingZone> damping;
  std::optional<SettlingSpec> settling;
  std::vector<geometry::BodyFillReport> fill;
  std::vector<geometry::MeshReport> meshes;
  double fill_seconds = 0.0;
  // Setup problems that do not stop the run (a fill level above its tank, a gauge inside a
  // solid, fluid outside every tank), one line each, for the run header and `swell fill`.
  std::vector<std::string> warnings;
  bool default_domain = true;  // the domain was computed (docs/user-guide/case-files.md), not given
  // Per body (index = body id): 1 for a boundary body with DBC walls in a run whose wall
  // module is mDBC (bodies[].boundary), else 0.
  std::vector<std::uint8_t> dbc_bodies;
  // A distributed set-up (several ranks): `particles` are this rank's share of the fill (ids as
  // the whole case's), `bodies` and `fill` count the whole case, and `order_lo`/`order_hi` are
  // the box of every particle, which the hydrostatic sort used: a rank that receives particles
  // restores the whole set's order with it (run/run.cpp).
  bool distributed = false;
  Vec<D> order_lo = Vec<D>::Zero(), order_hi = Vec<D>::Zero();
};

// The memory a run of about `particles` particles needs (setup and time loop together), and
// the memory this machine has available (MemAvailable, or the cgroup's limit if lower).
// Per particle: from the measured figures of the case's features (dimension, mDBC, moving
// bodies, shifting), with a margin.
double bytes_per_particle(const CaseSpec& spec, int dim);
double estimated_bytes(double particles, double grid_cells, double per_particle);
double available_memory_bytes();
// The memory this process holds now (resident set).
double resident_bytes();

// Builds the particles (geometry/), hydrostatic densities (bc/) and solver parameters. Mesh
// files are read relative to the case file's folder. Throws CaseError (file and line) for a
// shape that cannot be built or a body that cannot be filled, and for a setup that cannot run:
// more particles or memory than the machine (or limits.max_particles) allows, estimated before
// the fill; fluid or walls outside an explicit domain; gauges outside the domain; an initial
// hydrostatic density outside physics.density_bounds.
// `red`: several ranks (a decomposed run) fill the lattice in shares along one axis, balanced
// by the bodies' estimated counts, each with a margin of one kernel support; the checks and
// the hydrostatic state read the reductions; each rank keeps its own share (the same
// particles, ids, densities and order as the whole case's, split).
template <int D>
CaseSetup<D> setup_case(const CaseSpec& spec, const SetupReduce& red = SetupReduce());

// The simulation of a set-up case: its wall model (DBC or mDBC) and step hooks, in this order:
// moving bodies (prescribe), shifting, damping zones, settling (all three after_integration).
// `particles` are the setup's (fresh start) or a checkpoint's (restart).
// `exchange`: a run on several ranks (parallel/halo.hpp), `particles` being this rank's
// share.
template <int D>
Simulation<D> make_simulation(const CaseSetup<D>& setup, ParticleSet<D> particles,
                              std::unique_ptr<Exchange<D>> exchange = nullptr);

// The halo width of a decomposed run: the kernel support, plus the reach of the mDBC ghost
// nodes (twice the longest wall normal of `particles`, the set-up's or a checkpoint's).
template <int D>
double halo_width(const SolverParams& params, const ParticleSet<D>& particles);

}  // namespace swell
