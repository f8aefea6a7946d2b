// Whole-run quantities watched during a run: fluid mass, kinetic energy, momentum and the
// surge front; and the blow-up watchdog. Cheap O(N) reductions, called between steps.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "solver/state/particle_set.hpp"
#include "solver/time/simulation.hpp"

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
    t.kinetic_energy += 0.5 * ps.mass[i] * ps.velocity(i).squaredNorm();
    t.momentum += ps.mass[i] * ps.velocity(i);
    t.max_speed = std::max(t.max_speed, ps.velocity(i).norm());
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

// How the whole-run checks combine what each process saw. One process: as it is. A decomposed
// run passes a reducer over its ranks with the same calls (run/run_view.hpp), and every rank
// then gets the same answers.
struct SingleProcess {
  double sum(double x) const { return x; }
  double min(double x) const { return x; }
  double max(double x) const { return x; }
  // The largest `value` over the processes; `payload` becomes that of the process holding it.
  template <std::size_t K>
  double max_with(double value, std::array<double, K>& /*payload*/) const {
    return value;
  }
};

// When a run counts as blown up (case file `watchdog:`, docs/user-guide/troubleshooting.md).
// Fractions are of the initial fluid mass; densities are factors of rho0; the penetration depth
// is in dp.
struct WatchdogLimits {
  int every = 10;                          // steps between checks (also before each checkpoint)
  double warn_excluded_fraction = 0.001;   // warn once when this much fluid mass is gone
  double max_excluded_fraction = 0.05;     // stop when this much is gone
  double max_density_factor = 2.0;         // stop on any density above f rho0 or below rho0 / f
  double penetration_depth = 2.0;          // fluid this many dp below the lowest wall particle...
  double max_penetrated_fraction = 0.001;  // ...in more than this fraction of the fluid: stop
};

// Watches a running Simulation for a blow-up: fluid mass lost (by face and reason), fluid gone
// through the floor (deeper than penetration_depth dp below the lowest fixed wall particle,
// within the walls' horizontal extent), densities far from rho0 (walls checked here, fluid
// through the simulation's worst density exclusion). check() throws InstabilityError naming
// the particle, place, time and likely cause. One O(N) pass, no allocation unless it reports.
template <int D>
class Watchdog {
 public:
  // `floor`: the lowest initial fluid level along "up" (CaseSetup::floor): water starting below
  // every wall is not a leak. The initial fluid mass counts excluded particles too (restart).
  // `sim`: the Simulation, or anything with its particles(), params(), time(), steps(),
  // excluded(), excluded_faces() and worst_density_exclusion() (run/run_view.hpp). `red`
  // combines the processes of a decomposed run (each passes its own particles).
  template <class Sim, class Reduce = SingleProcess>
  Watchdog(const WatchdogLimits& limits, const Sim& sim, double floor, const Reduce& red = {})
      : lim_(limits) {
    const ParticleSet<D>& ps = sim.particles();
    const Vec<D> g = sim.params().gravity.template head<D>();
    for (int d = 0; d < D; ++d)
      if (std::abs(g[d]) > std::abs(g[up_])) up_ = d;
    sign_ = g[up_] > 0.0 ? -1.0 : 1.0;
    dp_ = sim.params().dp;
    rho0_ = sim.params().rho0;
    lo_.setConstant(std::numeric_limits<double>::infinity());
    hi_.setConstant(-std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < ps.total(); ++i) {
      if (is_fluid(ps.role[i])) {
        mass0_ += ps.mass[i];
        ++fluid0_;
      } else if (ps.role[i] == Role::FixedWall && i < ps.size()) {
        lo_ = lo_.cwiseMin(ps.pos[i]);
        hi_ = hi_.cwiseMax(ps.pos[i]);
      }
    }
    mass0_ = red.sum(mass0_);
    fluid0_ = static_cast<std::size_t>(red.sum(static_cast<double>(fluid0_)));
    for (int d = 0; d < D; ++d) lo_[d] = red.min(lo_[d]), hi_[d] = red.max(hi_[d]);
    bottom_ = std::min(sign_ > 0.0 ? lo_[up_] : -hi_[up_], floor) - limits.penetration_depth * dp_;
    walls_ = std::isfinite(lo_[up_]);
  }

  bool due(long step) const { return step % lim_.every == 0; }
  // The case's body names (by body index), for messages that name a wall particle's body.
  void set_body_names(std::vector<std::string> names) { body_names_ = std::move(names); }
  // Fluid mass excluded so far, as a fraction of the initial fluid mass (after check()).
  double excluded_fraction() const { return excluded_; }
  bool warned() const { return warned_; }
  const WatchdogLimits& limits() const { return lim_; }

  // Returns true once, when the excluded fluid mass first passes warn_excluded_fraction; the
  // warning text is then in warning(). Throws InstabilityError when a limit is passed.
  template <class Sim, class Reduce = SingleProcess>
  bool check(const Sim& sim, const Reduce& red = {}) {
    const ParticleSet<D>& ps = sim.particles();
    double mass = 0.0, wall_rho = 0.0, deepest = 0.0;
    std::size_t wall_i = ps.size(), deep_i = ps.size(), penetrated = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (!is_fluid(ps.role[i])) {
        if (ps.rho[i] > wall_rho) wall_rho = ps.rho[i], wall_i = i;
        continue;
      }
      mass += ps.mass[i];
      if (!walls_) continue;
      const double depth = bottom_ - sign_ * ps.pos[i][up_];
      if (depth <= 0.0) continue;
      bool under = true;
      for (int d = 0; d < D; ++d)
        if (d != up_) under = under && ps.pos[i][d] >= lo_[d] && ps.pos[i][d] <= hi_[d];
      if (!under) continue;
      ++penetrated;
      if (depth > deepest) deepest = depth, deep_i = i;
    }
    // The densest wall particle and the deepest fluid one (id, body, position) of the run.
    std::array<double, D + 2> wall{}, deep{};
    auto describe = [&](std::size_t i, std::array<double, D + 2>& out) {
      if (i >= ps.size()) return;
      out[0] = ps.id[i];
      out[1] = ps.body[i];
      for (int d = 0; d < D; ++d) out[static_cast<std::size_t>(2 + d)] = ps.pos[i][d];
    };
    describe(wall_i, wall);
    describe(deep_i, deep);
    mass = red.sum(mass);
    penetrated = static_cast<std::size_t>(red.sum(static_cast<double>(penetrated)));
    wall_rho = red.max_with(wall_rho, wall);
    deepest = red.max_with(deepest, deep);
    auto pos_of = [](const std::array<double, D + 2>& a) {
      Vec<D> x;
      for (int d = 0; d < D; ++d) x[d] = a[static_cast<std::size_t>(2 + d)];
      return x;
    };
    excluded_ = mass0_ > 0.0 ? std::max(0.0, 1.0 - mass / mass0_) : 0.0;
    const double t = sim.time();
    const long step = sim.steps();

    if (excluded_ > lim_.max_excluded_fraction) throw_excluded(sim, t, step);
    // (wall_rho > 0: a wall particle was seen)
    if (wall_rho > 0.0 && wall_rho > lim_.max_density_factor * rho0_) {
      std::ostringstream m;
      const auto body = static_cast<std::size_t>(wall[1]);
      m << "wall particle " << static_cast<std::uint64_t>(wall[0]) << " (body "
        << (body < body_names_.size() ? "'" + body_names_[body] + "'" : std::to_string(body))
        << ") at " << where(pos_of(wall)) << " has density " << wall_rho / rho0_
        << " rho0 at t = " << t << " s (step " << step
        << "), over watchdog.max_density = " << lim_.max_density_factor << " rho0 (pressure "
        << pressure_factor(wall_rho / rho0_)
        << ". Likely cause: an impact too violent for the wall (raise physics.coefsound, lower "
        << "time.cfl, or refine dp)";
      throw InstabilityError(m.str());
    }
    const auto& worst = sim.worst_density_exclusion();
    if (worst.ratio > lim_.max_density_factor) {
      std::ostringstream m;
      m << "fluid particle " << worst.id << " at " << where(worst.pos) << " reached density "
        << worst.rho / rho0_ << " rho0 at t = " << worst.time << " s, beyond watchdog.max_density "
        << "= " << lim_.max_density_factor << " (factor of rho0 either way) in one step"
        << ". Likely cause: the pressure field blew up (the speed of sound c0 = " << sim.params().c0
        << " m/s is too low for the flow, or time.cfl too high)";
      throw InstabilityError(m.str());
    }
    if (penetrated > lim_.max_penetrated_fraction * static_cast<double>(fluid0_)) {
      std::ostringstream m;
      m << penetrated << " fluid particles are more than " << lim_.penetration_depth
        << " dp below the lowest wall particle (the floor), within the walls' horizontal extent, "
        << "at t = " << t << " s (step " << step
        << "), over watchdog.max_penetrated = " << lim_.max_penetrated_fraction
        << " of the fluid; the deepest, particle " << static_cast<std::uint64_t>(deep[0]) << " at "
        << where(pos_of(deep)) << ", is " << deepest + lim_.penetration_depth * dp_
        << " m below it. Likely cause: water went through the DBC floor (the flow is too fast "
        << "for the wall: more layers, a smaller time.cfl or dp, or a higher physics.coefsound)";
      throw InstabilityError(m.str());
    }
    if (!warned_ && excluded_ > lim_.warn_excluded_fraction) {
      warned_ = true;
      std::ostringstream m;
      m << "warning: " << percent(excluded_)
        << " % of the fluid mass has been excluded by t = " << t << " s (step " << step
        << "), over watchdog.warn_excluded = " << percent(lim_.warn_excluded_fraction)
        << " %: " << by_face(sim);
      warning_ = m.str();
      return true;
    }
    return false;
  }
  const std::string& warning() const { return warning_; }

  // "N through x+ (t = a-b s), ..., M density out of range, K non-finite" for messages.
  template <class Sim>
  static std::string by_face(const Sim& sim) {
    const FaceExclusions& f = sim.excluded_faces();
    std::ostringstream m;
    const char* sep = "";
    for (int k = 0; k < FaceExclusions::kFaces; ++k) {
      const auto u = static_cast<std::size_t>(k);
      if (f.particles[u] == 0) continue;
      m << sep << f.fluid[u] << " fluid (" << f.particles[u] << " in all) out through "
        << FaceExclusions::name(k) << " (t = " << f.first_time[u] << "-" << f.last_time[u] << " s)";
      sep = ", ";
    }
    const ExclusionCounts& e = sim.excluded();
    m << sep << e.density_out_of_range << " density out of range, " << e.non_finite
      << " non-finite";
    return m.str();
  }

 private:
  static double percent(double f) { return std::round(f * 1e5) / 1e3; }
  static std::string where(const Vec<D>& x) {
    std::ostringstream m;
    m << "(";
    for (int d = 0; d < D; ++d) m << (d ? ", " : "") << x[d];
    m << ") m";
    return m.str();
  }
  std::string pressure_factor(double r) const {
    std::ostringstream m;
    m << "(rho/rho0)^7 = " << std::pow(r, 7.0) << ")";
    return m.str();
  }

  template <class Sim>
  [[noreturn]] void throw_excluded(const Sim& sim, double t, long step) const {
    const FaceExclusions& f = sim.excluded_faces();
    const ExclusionCounts& e = sim.excluded();
    int face = -1;
    for (int k = 0; k < FaceExclusions::kFaces; ++k)
      if (f.fluid_mass[static_cast<std::size_t>(k)] > 0.0 &&
          (face < 0 || f.fluid_mass[static_cast<std::size_t>(k)] >
                           f.fluid_mass[static_cast<std::size_t>(face)]))
        face = k;
    const double face_mass = face >= 0 ? f.fluid_mass[static_cast<std::size_t>(face)] : 0.0;
    std::ostringstream m;
    m << percent(excluded_) << " % of the fluid mass has been excluded by t = " << t << " s (step "
      << step << "), over watchdog.max_excluded = " << percent(lim_.max_excluded_fraction)
      << " %: " << by_face(sim) << ".";
    if (face >= 0) {
      const auto u = static_cast<std::size_t>(face);
      m << " Last through " << FaceExclusions::name(face) << ": particle " << f.last_id[u]
        << " at (" << f.last_pos[u][0] << ", " << f.last_pos[u][1];
      if (D == 3) m << ", " << f.last_pos[u][2];
      m << ") m at t = " << f.last_time[u] << " s.";
    }
    m << " Likely cause: ";
    const double per = mass0_ / std::max<std::size_t>(fluid0_, 1);
    const double density_mass = static_cast<double>(e.density_out_of_range) * per;
    if (e.non_finite > 0 && static_cast<double>(e.non_finite) * per >= face_mass &&
        static_cast<double>(e.non_finite) >= static_cast<double>(e.density_out_of_range)) {
      m << "the state turned non-finite (a numerical blow-up: lower time.cfl, raise "
           "physics.coefsound)";
    } else if (density_mass >= face_mass) {
      m << "the pressure field blew up: the fluid density left physics.density_bounds (the speed "
           "of sound c0 = "
        << sim.params().c0
        << " m/s too low for the flow, time.cfl too high, or an initial overlap)";
    } else if (face == 2 * up_ + (sign_ > 0.0 ? 0 : 1)) {
      m << "water is leaving through the bottom of the domain, i.e. through the floor (a DBC leak: "
           "more wall layers, a smaller time.cfl or dp, a higher physics.coefsound)";
    } else if (face == 2 * up_ + (sign_ > 0.0 ? 1 : 0)) {
      m << "splashes leave through the top of the domain; raise domain.max (or leave the domain "
           "to its default)";
    } else {
      m << "water is leaving through a side of the domain (over an open side, or through a wall "
           "that leaks); enlarge the domain or check the walls";
    }
    throw InstabilityError(m.str());
  }

  WatchdogLimits lim_;
  std::vector<std::string> body_names_;
  int up_ = D - 1;
  double sign_ = 1.0, dp_ = 0.0, rho0_ = 1000.0, bottom_ = 0.0;
  double mass0_ = 0.0;
  std::size_t fluid0_ = 0;
  Vec<D> lo_, hi_;
  bool walls_ = false;
  double excluded_ = 0.0;
  bool warned_ = false;
  std::string warning_;
};

}  // namespace swell
