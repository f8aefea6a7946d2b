// The run's clock and counters: what a restart needs besides the particles and the hooks' own
// state to continue a run bit for bit (io/hdf5_file writes it into checkpoints).
#pragma once

#include <cstddef>
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
