// Run-time parameters of the WCSPH solver. Plain data; filled by apps/ from the case file.
#pragma once

#include <Eigen/Core>
#include <array>

#include "solver/physics/kernels.hpp"

namespace swell {

enum class ViscosityModel { Artificial, Laminar };
enum class DiffusionModel { None, MolteniColagrossi, Fourtakas };
enum class IntegratorType { Symplectic, Verlet };
// The wall model (bc/): dynamic boundary conditions or modified DBC (English et al. 2022).
enum class BoundaryType { Dbc, Mdbc };
// mDBC: the velocity a wall particle shows the fluid. Wall: its body's velocity (as DBC and
// DualSPHysics' default); NoSlip: 2 v_body - v_ghost; FreeSlip: the ghost velocity with its
// normal component mirrored about the body's.
enum class MdbcSlip { Wall, NoSlip, FreeSlip };
// How an mDBC wall particle's density follows from its ghost node's (bc/mdbc.hpp).
enum class MdbcPressure { Linear, Hydrostatic };
// Particle shifting after each step (solver/physics/shifting.hpp): none, or Fickian (Lind et
// al. 2012 with Skillen et al. 2013's coefficient, tangential only at the free surface).
enum class ShiftingModel { None, Fickian };
// Which fluid particles near walls are shifted (DualSPHysics' ShiftMode): every one (full), none
// with a wall particle within the kernel support (nobound), none with a fixed-wall particle
// there (nofixed: near moving walls such as paddles they are shifted).
enum class ShiftMode : std::uint8_t { Full, NoBound, NoFixed };

struct SolverParams {
  double dp = 0.0;
  double h = 0.0;  // smoothing length, h = coefh sqrt(D) dp
  KernelType kernel = KernelType::Wendland;
  double rho0 = 1000.0;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, -9.81, 0.0);
  double c0 = 0.0;     // reference speed of sound, c0 = coefsound sqrt(g H)
  double gamma = 7.0;  // Tait exponent
  ViscosityModel viscosity = ViscosityModel::Artificial;
  double alpha = 0.01;  // Monaghan artificial viscosity
  double nu = 1.0e-6;   // laminar kinematic viscosity [m^2/s]
  DiffusionModel diffusion = DiffusionModel::Fourtakas;
  double delta = 0.1;
  IntegratorType integrator = IntegratorType::Symplectic;
  int verlet_steps = 40;  // Verlet: one Euler step every verlet_steps steps
  double cfl = 0.2;
  // A fixed time step [s] instead of the CFL choice (0: variable, the default; case key
  // time.dt_fixed; the temporal convergence study, verify/flows.cpp, uses it).
  double fixed_dt = 0.0;
  // Fluid particles whose density leaves [rho_min, rho_max] * rho0 are excluded (as
  // DualSPHysics' RhopOut); boundary density never drops below rho0 (DBC).
  double rho_min_factor = 0.7, rho_max_factor = 1.3;
  // A step whose dt falls below this fraction of the first dt is taken as a blow-up.
  double dt_collapse_factor = 1e-3;
  BoundaryType boundary = BoundaryType::Dbc;
  MdbcSlip mdbc_slip = MdbcSlip::Wall;
  MdbcPressure mdbc_pressure = MdbcPressure::Linear;
  // mDBC: below this determinant of the ghost node's correction matrix the first-order
  // extrapolation is replaced by a Shepard average (DualSPHysics' default, 1e-3).
  double mdbc_det_min = 1e-3;
  ShiftingModel shifting = ShiftingModel::None;
  double shift_coefficient = 2.0;        // A in dr = -A h |v| dt grad C
  double shift_surface_threshold = 0.0;  // div r below it: free surface (0: 1.5 in 2D, 2.75 in 3D)
  bool shift_correct_density = false;    // rho += dr . grad rho with each shift
  ShiftMode shift_mode = ShiftMode::Full;  // near walls: full | nobound | nofixed
  // Corrections (solver/time/correction_hooks.hpp), off by default.
  bool kernel_gradient_correction = false;
  double kgc_det_min = 0.1;  // below it the moment matrix counts as singular: no correction
  int shepard_reinit = 0;    // steps between Shepard density re-initialisations (0: never)
  Eigen::Vector3d domain_min = Eigen::Vector3d::Zero(), domain_max = Eigen::Vector3d::Zero();
  // Periodic axes (solver/neighbours/cell_grid.hpp): the domain's extent is the period.
  std::array<bool, 3> periodic{false, false, false};

  double eta2() const { return 0.01 * h * h; }
  double tait_b() const { return c0 * c0 * rho0 / gamma; }
};

}  // namespace swell
