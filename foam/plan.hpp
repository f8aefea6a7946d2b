// The mesh and sampling plan behind `swell foam`, computed from a CaseSpec before any file is
// written: the Cartesian grid spanning the tank, the cells each obstacle removes, the initial
// water cells, and where every gauge samples. Internal to foam/ (and its tests).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "case/spec.hpp"
#include "foam/foam.hpp"

namespace swell::foam {

// The blockMesh grid: one block spanning the tank box. In 2D the grid is one cell thick in z,
// centred on z = 0 (front and back faces are `empty`).
struct Grid {
  int dim = 2;
  int up = 1;  // vertical axis: y in 2D, z in 3D (as the SPH gauges)
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();
  Eigen::Vector3i n = Eigen::Vector3i::Ones();     // cells per axis
  Eigen::Vector3d cell = Eigen::Vector3d::Zero();  // cell size per axis (extent / n)
  long count() const { return static_cast<long>(n[0]) * n[1] * n[2]; }
  // blockMesh numbering of a single hex block: x fastest, then y, then z.
  long index(int i, int j, int k) const {
    return i + static_cast<long>(n[0]) * (j + static_cast<long>(n[1]) * k);
  }
  Eigen::Vector3d centre(long c) const;
  // Cell holding x (clamped to the grid).
  Eigen::Vector3i locate(const Eigen::Vector3d& x) const;
};

struct Obstacle {
  std::string name;  // body name, also the wall patch of its exposed faces
  bool is_box = false;
  Eigen::Vector3d box_min, box_max;  // boxes: topoSet boxToCell
  std::vector<long> cells;           // cells removed (original blockMesh numbering), ascending
  std::vector<long> labels;  // the same cells in the numbering of the mesh they are cut from
};

struct FluidBox {
  std::string body;
  Eigen::Vector3d min, max;  // setFields boxToCell
};

// One gauge as sampled by OpenFOAM. Points are in the mesh's coordinates (2D: z = 0).
struct Probe {
  GaugeSpec spec;
  double every = 0.0;                               // sampling interval [s]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // pressure, velocity
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();  // height
  std::vector<Eigen::Vector3d> line_starts, line_ends;  // front: lines along x
  int points = 0;                                       // height, front: points per line
  double level = 0.0;                                   // front: the floor (row bottom)
  std::vector<std::string> patches;                     // force
  Eigen::Vector3d cofr = Eigen::Vector3d::Zero();       // force: moment reference
  std::string function;                                 // the function object it belongs to
  bool skipped = false;                                 // not sampled (see Plan::notes)
};

// A piston wave paddle mapped to interFoam's waveModels (constant/waveProperties): the paddle
// face becomes patch `inlet` (waveVelocity / waveAlpha), the far end wall patch `outlet`
// (shallowWaterAbsorption) where the case has a damping zone.
struct WaveInlet {
  bool present = false;
  std::string body;     // the paddle body
  std::string model;    // StokesI, StokesII, Boussinesq (the 1912 solitary model)
  double height = 0.0;  // H [m]
  double period = 0.0;  // T [s] (regular)
  double depth = 0.0;   // waterDepthRef [m]
  double phase = 0.0;   // wavePhase [rad] (regular)
  double ramp = 0.0;    // rampTime [s] (regular)
  double x0 = 0.0;      // the inlet: the paddle's fluid-side face at rest [m]
  bool absorbing_outlet = false;
};

struct Plan {
  std::string case_name;
  // OpenFOAM t = 0 is case time `time_offset` (a wave paddle's start, and for a solitary wave
  // the shift that puts its crest at the inlet when the SPH paddle's would be); gauge times
  // are written in case time.
  double time_offset = 0.0;
  // 2D wave cases: OpenFOAM's vertical is z (1912's waveModels assume it; with gravity along
  // -y the run dies of a floating-point exception within 10 steps, measured), so the case's
  // (x, y) are written as OpenFOAM's (x, z) and its thin direction is y. The grid, obstacles and
  // probes below stay in case coordinates; foam() maps a point (a swap, its own inverse).
  bool z_up = false;
  Eigen::Vector3d foam(const Eigen::Vector3d& v) const {
    return z_up ? Eigen::Vector3d(v[0], v[2], v[1]) : v;
  }
  WaveInlet wave;
  Grid grid;
  double cell_size = 0.0;  // nominal size asked for
  double end_time = 0.0;
  double write_interval = 0.0;
  double rho_water = 1000.0;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  std::string tank;                    // tank body (its walls form patch `tank`)
  std::vector<std::string> open;       // open tank faces (patch `atmosphere`)
  std::vector<Obstacle> obstacles;     // cut out one after the other
  std::vector<FluidBox> fluid_boxes;   // setFields regions
  std::vector<unsigned char> removed;  // per original cell: 1 if cut out
  std::vector<unsigned char> wet;      // per original cell: initial alpha.water (0/1)
  bool alpha_by_list = false;          // some water is not a box: 0/alpha.water lists values
  long kept_cells = 0;
  std::vector<Probe> probes;
  std::vector<std::string> notes;
};

// Computes the plan. Throws std::invalid_argument for cases it cannot mesh.
Plan make_plan(const CaseSpec& spec, const FoamOptions& opt);

// The face names used for the box tank, in blockMesh order: xmin xmax ymin ymax zmin zmax.
extern const char* const kFaceNames[6];

// Sampling interval of a gauge: its own, else output.gauge_every, else output.every / 10.
double gauge_interval(const CaseSpec& spec, const GaugeSpec& g);

// OpenFOAM-safe word from a gauge or body name.
std::string foam_word(const std::string& s);

// The surge front along a row of cells [x0 + i dx, x0 + (i+1) dx) with water fractions
// `alpha` (NaN where the cell is cut out: a solid). From the first wet cell (alpha >= 0.5) the
// run of wet cells is followed, crossing solid gaps; the front is the far face of its last cell
// plus the water fraction of the next cell. NaN if no cell is wet.
double front_from_row(const std::vector<double>& alpha, double x0, double dx);
// Water level from alpha.water sampled at z0 + k ds along a vertical line (height gauges):
// the integral z0 + int alpha dz (trapezoid; `level: integral`), or the first free surface
// above the start, where alpha first falls below 0.5 (interpolated; `level: surface`; z0 if
// the bottom of the line is dry).
double level_integral(const std::vector<double>& alpha, double z0, double ds);
double level_surface(const std::vector<double>& alpha, double z0, double ds);

// What an interFoam log says about the run: steps, last time and step, and the problem if any
// (empty when it finished cleanly). `status` is the exit status, `stopped` the reason the run
// was stopped by the watcher (empty if not).
struct SolverLog {
  long steps = 0;
  double last_time = 0.0;
  double min_dt = 1e300, max_dt = 0.0, last_dt = 0.0;
  double courant_max = 0.0;            // the last step's "Courant Number ... max:" (0: none yet)
  double interface_courant_max = 0.0;  // the last step's "Interface Courant Number ... max:"
  bool nan = false, fatal = false, fpe = false, finished = false;
  std::string problem;
  FoamError::Kind kind = FoamError::Kind::Diverged;
};
SolverLog check_solver_log(const std::string& log, double end_time, int status,
                           const std::string& stopped);

// One line of `swell foam --run` progress from the solver log so far: simulated time of
// end_time, steps, dt, Courant numbers, elapsed wall time and the time left at the mean rate.
std::string progress_line(const SolverLog& s, double end_time, double elapsed_seconds);

// Writes every dictionary of the case into dir (system/, constant/, 0.orig/).
void write_case_files(const Plan& plan, const std::string& dir);

}  // namespace swell::foam
