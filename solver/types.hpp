// Basic types shared by the solver: fixed-size Eigen vectors and particle tags.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace swell {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

// What a particle is. Fluid particles move under the momentum equation; boundary
// particles (DBC) keep prescribed positions but evolve their density.
enum class Kind : std::uint8_t { Fluid = 0, Boundary = 1 };

// Why a particle was taken out of the simulation (DESIGN.md: excluded and counted).
enum class Exclusion : std::uint8_t { None = 0, OutOfDomain = 1, NonFinite = 2 };

}  // namespace swell
