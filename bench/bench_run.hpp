// One timed benchmark run: step a Simulation to an end time (or for a number of steps) with no
// output and report particle-steps per second, phase times and memory. Depends on solver/ only;
// `swell bench` (apps/bench_command.cpp) builds the particles and runs each measurement in a
// fresh process so that peak memory is the run's own.
#pragma once

#include <omp.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "solver/time/simulation.hpp"

namespace swell::bench {

struct RunResult {
  std::size_t particles = 0, fluid = 0;
  long steps = 0;
  double sim_time = 0.0;
  double wall = 0.0;   // seconds in the time loop
  PhaseTimes phases;   // neighbour sort, interaction, integration [s]
  double other = 0.0;  // time loop minus the three phases (dt choice, bounds check, loop) [s]
  double particle_steps_per_second() const {
    return wall > 0.0 ? static_cast<double>(particles) * static_cast<double>(steps) / wall : 0.0;
  }
};

// Kibibytes from a "Key:   123 kB" line of /proc/self/status (0 where unavailable).
inline long proc_status_kb(const char* key) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  long kb = 0;
  const std::size_t n = std::strlen(key);
  while (std::fgets(line, sizeof line, f)) {
    if (std::strncmp(line, key, n) == 0 && line[n] == ':') {
      kb = std::strtol(line + n + 1, nullptr, 10);
      break;
    }
  }
  std::fclose(f);
  return kb;
}

// Steps `sim` until time t_end, or for max_steps steps when max_steps > 0 (scaling sweep).
// The time loop's own wall time is measured; setup is not.
template <int D>
RunResult time_run(Simulation<D>& sim, double t_end, long max_steps) {
  RunResult r;
  r.particles = sim.particles().size();
  r.fluid = sim.fluid_count();
  const PhaseTimes before = sim.phase_times();
  const long steps0 = sim.steps();
  const double t0 = omp_get_wtime();
  if (max_steps > 0) {
    for (long s = 0; s < max_steps; ++s) sim.step();
  } else {
    while (sim.time() < t_end) sim.step();
  }
  r.wall = omp_get_wtime() - t0;
  r.steps = sim.steps() - steps0;
  r.sim_time = sim.time();
  const PhaseTimes& after = sim.phase_times();
  r.phases.neighbour = after.neighbour - before.neighbour;
  r.phases.interaction = after.interaction - before.interaction;
  r.phases.integration = after.integration - before.integration;
  r.other = r.wall - r.phases.neighbour - r.phases.interaction - r.phases.integration;
  return r;
}

}  // namespace swell::bench
