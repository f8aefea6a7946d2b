// Basic types shared by the solver: fixed-size Eigen vectors and particle roles.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>

namespace swell {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

// Storage precision of the evolved velocity and density and of their integrator copies (issue
// #16, leaner state): float, as DualSPHysics keeps them, with positions, masses and every
// computation in double (values are widened where they are read and rounded once where the
// integrator stores them). 24 B per particle less in 2D, 32 B in 3D. A build with
// -DSWELL_DOUBLE_STATE=ON keeps them in double (the state before 2026-12-05, for comparisons).
#ifdef SWELL_DOUBLE_STATE
using StateReal = double;
#else
using StateReal = float;
#endif
template <int D>
using StateVec = Eigen::Matrix<StateReal, D, 1>;
// Arithmetic type of the WCSPH pair terms (issue #16: twice the SIMD lanes of double). Positions
// stay double and each pair's r_ab is their difference taken in double, then rounded (as
// DualSPHysics' CPU code does), so the rounding is relative to r_ab, never to the coordinates;
// kernel, pressure, viscosity and diffusion terms and the per-particle sums are in PairReal.
// The double-state build keeps double arithmetic, bit for bit as before.
using PairReal = StateReal;
// Relative rounding of a value when it is stored (half of it: round to nearest).
inline constexpr double kStateEps = std::numeric_limits<StateReal>::epsilon();
// A stored velocity in double for arithmetic, and a computed one rounded for storage.
template <int D>
inline Vec<D> widen(const StateVec<D>& v) {
  return v.template cast<double>();
}
template <int D>
inline StateVec<D> narrow(const Vec<D>& v) {
  return v.template cast<StateReal>();
}

// What a particle does in the step. Fluid particles move under the momentum equation; wall
// particles (any boundary model) evolve their density but not under the momentum equation: a
// fixed wall keeps its position, a moving wall takes position and velocity from its body's
// motion law (bc/motion), a floating wall (reserved) will move with the rigid-body equations.
// The values are stored in checkpoints and in snapshots (dataset "type"): never renumber them.
enum class Role : std::uint8_t { Fluid = 0, FixedWall = 1, MovingWall = 2, Floating = 3 };

inline constexpr bool is_fluid(Role r) {
  return r == Role::Fluid;
}
inline constexpr bool is_wall(Role r) {
  return r != Role::Fluid;
}
inline constexpr bool is_valid_role(std::uint8_t r) {
  return r <= 3;
}
inline const char* role_name(Role r) {
  switch (r) {
    case Role::Fluid:
      return "fluid";
    case Role::FixedWall:
      return "fixed wall";
    case Role::MovingWall:
      return "moving wall";
    case Role::Floating:
      return "floating";
  }
  return "unknown";
}

// Why a particle was taken out of the simulation (never deleted: excluded and counted).
enum class Exclusion : std::uint8_t { None = 0, OutOfDomain = 1, NonFinite = 2 };

}  // namespace swell
