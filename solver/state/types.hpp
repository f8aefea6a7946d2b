// Basic types shared by the solver: fixed-size Eigen vectors and particle roles.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace swell {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

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

// Why a particle was taken out of the simulation (DESIGN.md: excluded and counted).
enum class Exclusion : std::uint8_t { None = 0, OutOfDomain = 1, NonFinite = 2 };

}  // namespace swell
