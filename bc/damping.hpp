// Absorption by damping zones, and a settling phase, as step hooks in after_integration.
//
// Damping zones (sponge layers: Israeli & Orszag 1981, J. Comput. Phys. 41; in SPH the damping
// zone of DualSPHysics, Altomare et al. 2017, Coastal Eng. 127). Once per step, after the
// integration, a fluid particle in a zone has its velocity relaxed towards zero,
//     v <- v exp(-sigma(s) dt),   sigma(s) = sigma_max r(s),
// where s in [0, 1] is its normalised depth into the zone and r the ramp: quadratic r = s^2
// (DualSPHysics' form) or cosine r = (1 - cos(pi s)) / 2 (zero slope at both ends). Altomare et
// al. multiply by 1 - dt sigma_max s^2 (their redumax is sigma_max); the exponential is the same
// to first order in dt, is exact for the relaxation dv/dt = -sigma v, and never changes the sign
// of v however large sigma dt is. Overlapping zones multiply their factors (their sigmas add).
// Shapes:
//   plane: s = clamp(((x - x0) . n) / L, 0, 1) where (x - x0) . n >= 0 (s = 1 beyond the far end);
//          untouched behind the plane;
//   box:   inside [min, max] only; s grows along n across the box, from 0 at the box's corner
//          furthest against n (for an axis direction: the face opposite to it) to 1 at the
//          opposite corner (L = sum_k |n_k| (max_k - min_k)).
// Each zone damps only the velocity components it names (all by default), and only while the
// step's midpoint lies in [start, stop).
//
// Settling: for t in [0, T) every fluid particle is relaxed the same way with
//     sigma(t) = sigma_0 (1 + cos(pi t / T)) / 2,
// which falls smoothly to 0 at t = T (zero slope there: no jolt when it ends). The factor of a
// step [t0, t1] is exp(-integral of sigma over [t0, min(t1, T)]), integrated exactly, so the
// whole phase relaxes a velocity left to itself by exactly exp(-sigma_0 T / 2) whatever the dt.
//
// Both hooks are stateless: the factor is a pure function of position, dt and time, so a
// restarted run continues bitwise, and nothing goes into the checkpoint. Positions are never
// changed: a damped particle just moves less in the next step.
//
// Interaction with the integrators (after_integration runs after the whole step):
//  - Symplectic: the step has moved x^{n+1} = x^{n+1/2} + dt/2 v^{n+1} with the undamped
//    v^{n+1}; the relaxation then acts on v^{n+1} (a first-order split: integrate, then relax).
//    vel_prev is overwritten from vel at the start of the next step, so only vel is damped.
//  - Verlet: the next step computes v^{n+2} = v^n + 2 dt a^{n+1} from vel_prev = v^n. Damping
//    vel alone would relax each of the two interleaved leapfrog sequences every other step only
//    (at sigma / 2) and pull them apart; vel_prev is therefore damped by the same factor, so each
//    sequence relaxes at sigma (the Euler step every verlet_steps steps uses vel, damped too).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "solver/state/particle_set.hpp"
#include "solver/time/step_hooks.hpp"

namespace swell {

enum class DampingRamp { Quadratic, Cosine };

// r(s) for s in [0, 1]: 0 at the zone's start, 1 at its far end.
inline double damping_ramp(DampingRamp ramp, double s) {
  return ramp == DampingRamp::Quadratic ? s * s : 0.5 * (1.0 - std::cos(std::numbers::pi * s));
}

// One damping zone as given in the case file (case/reader.cpp reads `damping:`). SI units.
struct DampingZone {
  // sigma_max [1/s]: the value DualSPHysics' damping examples use (redumax = 10). Averaged over
  // the zone's length sigma is sigma_max / 3 with the quadratic ramp, sigma_max / 2 with the
  // cosine one.
  static constexpr double kDefaultRate = 10.0;
  enum class Shape { Plane, Box };
  std::string name;
  Shape shape = Shape::Plane;
  Eigen::Vector3d at = Eigen::Vector3d::Zero();          // plane: a point of the start plane
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // into the zone (normalised on use)
  double length = 0.0;                                   // plane: L [m], > 0
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero();     // box
  Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
  DampingRamp ramp = DampingRamp::Quadratic;
  double rate = kDefaultRate;                             // sigma_max [1/s], > 0
  std::array<bool, 3> components = {true, true, true};    // which velocity components
  double start = 0.0;                                     // [s]
  double stop = std::numeric_limits<double>::infinity();  // [s], > start
};

// Throws std::invalid_argument naming what is wrong (a zero direction, length or box extent
// <= 0, rate <= 0, no component, stop <= start) in a zone of a `dim`-dimensional case.
void check_damping_zone(const DampingZone& zone, int dim);

// A zone reduced to what the step needs: s = (x - origin) . n * inv_length, clamped, and for a
// box the box itself (outside it nothing is damped).
struct DampingGeometry {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::UnitX();  // unit
  double length = 1.0;
  double inv_length = 1.0;
  bool box = false;
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
};

// The geometry of a checked zone (check_damping_zone first).
DampingGeometry damping_geometry(const DampingZone& zone, int dim);

// Depth s in [0, 1] of x in the zone, or -1 where the zone does not act (behind a plane zone's
// start, outside a box zone).
template <int D>
double damping_depth(const DampingGeometry& g, const Vec<D>& x) {
  if (g.box) {
    for (int d = 0; d < D; ++d)
      if (x[d] < g.lo[d] || x[d] > g.hi[d]) return -1.0;
  }
  const double along = (x - g.origin.template head<D>()).dot(g.n.template head<D>());
  if (along < 0.0) return -1.0;
  return std::min(along * g.inv_length, 1.0);
}

// The settling phase, `time.settling` in the case file.
struct SettlingSpec {
  // sigma_0 [1/s]: the damping zones' default, so one relaxation rate is all there is to
  // remember; the whole phase then relaxes a free velocity by exp(-5) at duration 1 s.
  static constexpr double kDefaultRate = 10.0;
  double duration = 0.0;  // T [s], > 0
  double rate = kDefaultRate;
};

// sigma(t) = sigma_0 (1 + cos(pi t / T)) / 2 on [0, T), 0 from T on (runs start at t = 0).
inline double settling_rate(const SettlingSpec& s, double t) {
  if (t >= s.duration) return 0.0;
  return 0.5 * s.rate * (1.0 + std::cos(std::numbers::pi * std::max(t, 0.0) / s.duration));
}

// The integral of settling_rate over [t0, t1] (0 <= t0 <= t1), exact: with u = clamp(t, 0, T),
// sigma_0 / 2 [u + T / pi sin(pi u / T)] between the two.
inline double settling_integral(const SettlingSpec& s, double t0, double t1) {
  const double T = s.duration;
  auto primitive = [&](double t) {
    const double u = std::clamp(t, 0.0, T);
    return 0.5 * s.rate * (u + T / std::numbers::pi * std::sin(std::numbers::pi * u / T));
  };
  return primitive(t1) - primitive(t0);
}

// Damping zones in after_integration: a parallel loop over the particles, fluid only.
template <int D>
class DampingZones final : public StepHook<D> {
 public:
  // Checks every zone (std::invalid_argument naming it).
  explicit DampingZones(std::vector<DampingZone> zones);
  std::string name() const override { return "damping"; }
  bool changes_state_before_forces() const override { return false; }
  bool reads_images_after_integration() const override { return false; }
  void after_integration(StepState<D>& s) override;
  const std::vector<DampingZone>& zones() const { return zones_; }

 private:
  std::vector<DampingZone> zones_;
  std::vector<DampingGeometry> geometry_;
  std::vector<Vec<D>> mask_;         // per zone: 1 for a damped component, 0 otherwise
  std::vector<std::size_t> active_;  // the zones acting in this step (capacity reserved)
};

// Settling in after_integration: every fluid particle's velocity by one factor per step.
template <int D>
class Settling final : public StepHook<D> {
 public:
  explicit Settling(const SettlingSpec& spec);  // std::invalid_argument unless T, rate > 0
  std::string name() const override { return "settling"; }
  bool changes_state_before_forces() const override { return false; }
  bool reads_images_after_integration() const override { return false; }
  void after_integration(StepState<D>& s) override;
  const SettlingSpec& spec() const { return spec_; }

 private:
  SettlingSpec spec_;
};

}  // namespace swell
