// Whole-run quantities watched during a run: fluid mass, kinetic energy, momentum and the
// surge front. Cheap O(N) reductions, called between steps.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/state/particle_set.hpp"

namespace swell {

template <int D>
struct FluidTotals {
  std::size_t count = 0;
  double mass = 0.0;
  double kinetic_energy = 0.0;
  Vec<D> momentum = Vec<D>::Zero();
  double max_speed = 0.0;
};

template <int D>
FluidTotals<D> fluid_totals(const ParticleSet<D>& ps) {
  FluidTotals<D> t;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.role[i] != Role::Fluid) continue;
    ++t.count;
    t.mass += ps.mass[i];
    t.kinetic_energy += 0.5 * ps.mass[i] * ps.vel[i].squaredNorm();
    t.momentum += ps.mass[i] * ps.vel[i];
    t.max_speed = std::max(t.max_speed, ps.vel[i].norm());
  }
  return t;
}

// Surge front along +x: the largest x reached by fluid within `band` above `floor` (heights
// measured along `up`), plus dp/2 so it marks the fluid's edge rather than a particle centre.
// Returns -inf when no fluid particle is in the band.
template <int D>
double surge_front(const ParticleSet<D>& ps, const Vec<D>& up, double floor, double band,
                   double dp) {
  double front = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.role[i] != Role::Fluid) continue;
    const double z = ps.pos[i].dot(up) - floor;
    if (z >= 0.0 && z <= band) front = std::max(front, ps.pos[i][0] + 0.5 * dp);
  }
  return front;
}

}  // namespace swell
