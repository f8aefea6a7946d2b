// The parsed, validated content of a case file. Plain data: case/reader.cpp fills it from
// YAML, case/setup turns it into particles (geometry/) and solver parameters (solver/).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "bc/damping.hpp"
#include "bc/motion.hpp"
#include "geometry/shape_spec.hpp"
#include "solver/diagnostics.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/solver_params.hpp"

namespace swell {

struct BodySpec {
  std::string name;
  enum class Kind { Fluid, Boundary };
  Kind kind = Kind::Fluid;
  // Fluid bodies may instead be given as `fill: {below: LEVEL, inside: BODY}`: every lattice
  // point below LEVEL (along the vertical axis) inside boundary body BODY's shape. `shape`
  // is then unused.
  ShapeSpec shape;
  std::optional<double> fill_below;
  std::string fill_inside;
  // The index of body `fill_inside` in CaseSpec::bodies, set (and checked to be a boundary body
  // with walls: inside) by the case-file reader; -1 without a fill. Code that inserts or
  // removes bodies of a parsed spec must keep it true.
  int fill_container = -1;
  // Boundary bodies: which side of the surface the wall particles go on.
  //   inside  - the fluid is inside the shape (a tank); particles fill `layers` outside it,
  //   outside - the fluid is outside the shape (a structure); particles fill `layers` inside it.
  enum class Walls { Inside, Outside };
  Walls walls = Walls::Inside;
  int layers = 3;
  // Faces of a box tank left open (no wall particles): any of xmin, xmax, ymin, ymax, zmin, zmax.
  std::vector<std::string> open;
  // Boundary bodies: prescribed motion (bc/motion.hpp); type None keeps the body fixed.
  MotionSpec motion;
  // Boundary bodies: this body's wall model; unset: the case's physics.boundary.model.
  std::optional<BoundaryType> boundary;
  int line = 0;  // line in the case file, for messages
};

// A measurement taken during the run (and by `swell probe` from saved snapshots).
struct GaugeSpec {
  enum class Kind { Pressure, Height, Velocity, Force, Front, Runup };
  std::string name;
  Kind kind = Kind::Pressure;
  // pressure, velocity: the point; height: the start of the vertical measuring line (its
  // horizontal position, and its vertical coordinate where the line starts, usually the floor).
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  // pressure: optional wall normal (pointing into the fluid); the probe then samples at
  // at + offset * normal, offset defaulting to h (DualSPHysics-style wall pressure probes).
  std::optional<Eigen::Vector3d> normal;
  std::optional<double> offset;
  // pressure with `size`: a sensor face on the wall (a disc of this diameter in 3D, a segment of
  // this length in 2D) centred at `at`, facing along `normal`: the face average of the fluid
  // pressure extrapolated to the wall, taken every step and written as the mean over each
  // sampling interval (solver/gauges.hpp face_pressure).
  std::optional<double> size;
  std::string body;                             // force: the boundary body name
  std::optional<Eigen::Vector3d> moment_about;  // force: moment reference point (default origin)
  std::optional<double> band;                   // front: band height above the floor (default 2h)
  // height: which water level. Surface: the first free surface above the start of the line
  // (DualSPHysics' GaugeSwl; a splash above a dry gap is not counted). Integral: the start plus
  // the integral of the water fraction along the line (interFoam's usual definition; splashes
  // and detached layers count). Both solvers compute both.
  enum class Level { Surface, Integral };
  Level level = Level::Surface;
  // height: `sampling: mean` evaluates the level after every step and writes the time mean over
  // each sampling interval (a wave gauge that misses no crest between two rows); `instant`
  // (the default) writes the level at the row's time.
  bool mean = false;
  // runup: the line along the slope surface, `from` (below the lowest shoreline) to `to`
  // (above the highest), and the still-water level the value is given relative to (absolute
  // elevation without it). `max` (`sampling: max`) evaluates the runup after every step and
  // writes the largest value of each interval (solver/gauges.hpp runup_elevation).
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
  std::optional<double> swl;
  bool max = false;
  bool connected = false;  // `edge: connected`: the tongue attached to the sea, not splashes
  double every = 0.0;      // sampling interval [s]; 0: output.gauge_every
  // `every: step`: a row after every step (the raw series; a sensor face's row is then its value
  // at that step, a runup maximum the step's value); `every` stays 0.
  bool every_step = false;
  int line = 0;
};

// The gauge kind as written in case files and in gauge file names (gauges_<kind>.csv).
inline const char* gauge_kind_name(GaugeSpec::Kind k) {
  switch (k) {
    case GaugeSpec::Kind::Pressure:
      return "pressure";
    case GaugeSpec::Kind::Height:
      return "height";
    case GaugeSpec::Kind::Velocity:
      return "velocity";
    case GaugeSpec::Kind::Force:
      return "force";
    case GaugeSpec::Kind::Front:
      return "front";
    case GaugeSpec::Kind::Runup:
      return "runup";
  }
  return "gauge";
}

// A damping zone (bc/damping.hpp) and where the case file gave it.
struct DampingSpec {
  DampingZone zone;
  int line = 0;
};

struct CaseSpec {
  std::string file;  // path of the case file, for messages
  std::string text;  // the case file as read, kept for metadata
  std::string name;
  int dim = 2;
  double dp = 0.0;

  // physics
  double rho0 = 1000.0;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, -9.81, 0.0);  // default: -y in 2D, -z in 3D
  double coefsound = 20.0;
  double coefh = 1.0;
  std::optional<double> hswl;  // still-water height for c0; default: from the fluid particles
  // Models: the solver's enums, read from their names (case/model_names.hpp) by the reader.
  KernelType kernel = KernelType::Wendland;  // wendland | cubic | quintic | gaussian
  ViscosityModel viscosity_model = ViscosityModel::Artificial;  // artificial | laminar
  double alpha = 0.01;                                          // artificial viscosity coefficient
  double nu = 1.0e-6;  // kinematic viscosity, laminar model [m^2/s]
  DiffusionModel diffusion_model = DiffusionModel::Fourtakas;  // fourtakas | molteni | none
  double delta = 0.1;
  double rho_min_factor = 0.7, rho_max_factor = 1.3;  // fluid density bounds before exclusion
  // Wall model: dbc | mdbc (bc/), and mDBC's slip mode and Shepard-fallback threshold.
  BoundaryType boundary = BoundaryType::Dbc;
  MdbcSlip mdbc_slip = MdbcSlip::Wall;
  MdbcPressure mdbc_pressure = MdbcPressure::Linear;
  double mdbc_det_min = 1e-3;
  // Particle shifting: none | fickian, its coefficient A and free-surface threshold on div r
  // (0: the default for the dimension).
  ShiftingModel shifting = ShiftingModel::None;
  // physics.corrections
  bool kernel_gradient_correction = false;
  double kgc_det_min = 0.1;
  int shepard_reinit = 0;
  double shift_coefficient = 2.0;
  double shift_surface_threshold = 0.0;
  bool shift_correct_density = false;      // rho += dr . grad rho with each shift
  ShiftMode shift_mode = ShiftMode::Full;  // near walls: full | nobound | nofixed

  // time
  double t_end = 0.0;
  double cfl = 0.2;
  double dt_fixed = 0.0;                                   // time.dt_fixed [s]; 0: the CFL step
  IntegratorType integrator = IntegratorType::Symplectic;  // symplectic | verlet
  int verlet_steps = 40;
  // time.settling: velocities relaxed over [0, duration) (bc/damping.hpp); none by default.
  std::optional<SettlingSpec> settling;

  // domain: particles leaving it are excluded. Default: boundary bounding box + margin.
  std::optional<Eigen::Vector3d> domain_min, domain_max;
  // domain.periodic: the periodic axes (x, y, z); none by default.
  std::array<bool, 3> periodic{false, false, false};

  std::vector<BodySpec> bodies;
  std::vector<GaugeSpec> gauges;
  std::vector<DampingSpec> damping;  // `damping:` zones, in case order

  // output
  double output_every = 0.0;  // 0: only the initial and final states
  bool vtk = true;
  bool vtk_split = false;         // also write fluid-only and boundary-only .vtp series
  bool hdf5 = true;               // snapshots + metadata in OUTDIR/<name>.h5
  double checkpoint_every = 0.0;  // 0: at every output time
  double gauge_every = 0.0;       // default gauge interval; 0: output.every / 10

  // watchdog: when a run counts as blown up (solver/diagnostics.hpp), and dt collapse
  WatchdogLimits watchdog;
  double dt_collapse = 1e-3;  // a dt below this fraction of the first one stops the run

  // limits: what a case may ask of the machine before the fill starts (case/setup.cpp)
  double max_particles = 5.0e7;
};

}  // namespace swell
