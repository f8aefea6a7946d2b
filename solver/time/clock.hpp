// The run's clock and counters: what a restart needs besides the particles and the hooks' own
// state to continue a run bit for bit (io/hdf5_file writes it into checkpoints).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

namespace swell {

// Thrown when the run cannot go on (time step collapse, every fluid particle lost).
class InstabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExclusionCounts {
  std::size_t out_of_domain = 0;
  std::size_t non_finite = 0;
  std::size_t density_out_of_range = 0;
  std::size_t total() const { return out_of_domain + non_finite + density_out_of_range; }
};

// Particles that left the domain, by the face they crossed (the one they are farthest
// beyond): x-, x+, y-, y+, z-, z+. Fluid mass and the first and last time per face tell a
// splash over an open top from water draining through a wall. Times are -1 until a face
// sees its first particle.
struct FaceExclusions {
  static constexpr int kFaces = 6;
  std::array<std::size_t, kFaces> particles{};
  std::array<std::size_t, kFaces> fluid{};
  std::array<double, kFaces> fluid_mass{};
  std::array<double, kFaces> first_time{-1.0, -1.0, -1.0, -1.0, -1.0, -1.0};
  std::array<double, kFaces> last_time{-1.0, -1.0, -1.0, -1.0, -1.0, -1.0};
  // The last fluid particle lost through each face (id, position x, y, z), for diagnostics.
  std::array<std::uint32_t, kFaces> last_id{};
  std::array<std::array<double, 3>, kFaces> last_pos{};

  static const char* name(int face) {
    static const char* const names[kFaces] = {"x-", "x+", "y-", "y+", "z-", "z+"};
    return names[face];
  }
  double total_fluid_mass() const {
    double m = 0.0;
    for (const double v : fluid_mass) m += v;
    return m;
  }
};

struct SimulationClock {
  double time = 0.0;
  long steps = 0;
  double dt = 0.0;
  double first_dt = 0.0;
  int verlet_counter = 0;
  ExclusionCounts excluded;
};

struct PhaseTimes {
  double neighbour = 0.0;    // cell sort and reordering [s]
  double interaction = 0.0;  // pressure, pair loop and time-step reductions [s]
  double integration = 0.0;  // predictor/corrector updates and the hooks around them [s]
};

}  // namespace swell
