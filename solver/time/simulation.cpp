#include "solver/time/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace swell {

template <int D>
Simulation<D>::Simulation(const SolverParams& params, ParticleSet<D> particles,
                          std::unique_ptr<BoundaryModel<D>> boundary, Hooks hooks,
                          std::unique_ptr<Exchange<D>> exchange)
    : prm_(params),
      eos_(params.rho0, params.c0, params.gamma),
      ps_(std::move(particles)),
      boundary_(std::move(boundary)),
      hooks_(std::move(hooks)),
      exchange_(std::move(exchange)) {
  if (!(prm_.h > 0.0) || !(prm_.c0 > 0.0) || !(prm_.dp > 0.0))
    throw std::invalid_argument("Simulation: h, c0 and dp must be positive");
  if (!(prm_.gamma > 1.0)) throw std::invalid_argument("Simulation: the Tait gamma must be > 1");
  if (!boundary_) throw std::invalid_argument("Simulation: a boundary model is required");
  for (const auto& h : hooks_)
    if (!h) throw std::invalid_argument("Simulation: null step hook");
  for (std::size_t i = 0; i < ps_.total(); ++i)
    if (ps_.role[i] == Role::Floating)
      throw std::invalid_argument(
          "Simulation: floating bodies are reserved but not implemented yet (particle id " +
          std::to_string(ps_.id[i]) + ")");
  const double support = kernel_support_factor(prm_.kernel) * prm_.h;
  grid_ =
      CellGrid<D>(prm_.domain_min.template head<D>(), prm_.domain_max.template head<D>(), support);
  std::array<bool, D> periodic{};
  for (int d = 0; d < D; ++d) periodic[d] = prm_.periodic[d];
  grid_.set_periodic(periodic);
  if (exchange_) {
    // The exchange builds the images (the halo, and across periodic faces) with the halo.
    grid_.set_images_by_exchange(true);
    exchange_->configure(grid_);
  }
  // The set-up's sorts may have allocated the set's own reorder scratch; the Simulation's sorts
  // borrow the force buffers instead (sort_particles).
  ps_.release_scratch();
  f_.resize(ps_.total());
  // Forces at the initial state, so acceleration() (wall loads) is valid before the first step.
  evaluate();
  grid_.drop_ghosts(ps_);
}

template <int D>
template <class Stage>
void Simulation<D>::for_each_hook(Stage&& stage) {
  stage(static_cast<StepHook<D>&>(*boundary_));
  for (auto& h : hooks_) stage(*h);
}

template <int D>
template <class Test>
bool Simulation<D>::any_hook(Test&& test) const {
  if (test(static_cast<const StepHook<D>&>(*boundary_))) return true;
  for (const auto& h : hooks_)
    if (test(*h)) return true;
  return false;
}

template <int D>
void Simulation<D>::restore(const SimulationClock& c) {
  time_ = c.time;
  steps_ = c.steps;
  dt_ = c.dt;
  first_dt_ = c.first_dt;
  verlet_counter_ = c.verlet_counter;
  // Particles excluded by the constructor's sort were still active when saved.
  excluded_.out_of_domain += c.excluded.out_of_domain;
  excluded_.non_finite += c.excluded.non_finite;
  excluded_.density_out_of_range += c.excluded.density_out_of_range;
}

template <int D>
void Simulation<D>::save_hooks(std::map<std::string, double>& out) const {
  auto one = [&](const StepHook<D>& h) {
    std::map<std::string, double> own;
    h.save(own);
    for (const auto& [k, v] : own) out["hook." + h.name() + "." + k] = v;
  };
  one(*boundary_);
  for (const auto& h : hooks_) one(*h);
}

template <int D>
void Simulation<D>::restore_hooks(const std::map<std::string, double>& in) {
  for_each_hook([&](StepHook<D>& h) {
    const std::string prefix = "hook." + h.name() + ".";
    std::map<std::string, double> own;
    for (auto it = in.lower_bound(prefix); it != in.end() && it->first.starts_with(prefix); ++it)
      own[it->first.substr(prefix.size())] = it->second;
    h.restore(own);
  });
}

template <int D>
std::size_t Simulation<D>::fluid_count() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < ps_.size(); ++i) n += is_fluid(ps_.role[i]);
  return n;
}

template <int D>
LentScratch<D> Simulation<D>::lent_force_buffers() {
  LentScratch<D> lent;
  lent.vec = &f_.ace;
  lent.dbl = {&f_.drho, &f_.prs};
  return lent;
}

template <int D>
void Simulation<D>::sort_particles(bool between_steps) {
  const double t0 = omp_get_wtime();
  const std::size_t before = ps_.size();
  typename CellGrid<D>::Reorder how;
  if (between_steps) {
    // The last evaluation's rates stay readable (wall loads, output): they follow the
    // particles, and no scratch is needed for this rare sort.
    how.in_place = true;
    how.follow_vec = &f_.ace;
    how.follow_dbl = &f_.drho;
  } else {
    // At the start of an evaluation the rates are dead until the forces refill them: the
    // reorder uses them as its scratch (ParticleSet::permute), so the set keeps none of its own
    // for those types.
    how.lent = lent_force_buffers();
  }
  const auto r = grid_.sort(ps_, how);
  excluded_.out_of_domain += r.out_of_domain;
  excluded_.non_finite += r.non_finite;
  if (r.out_of_domain > 0) record_faces(ps_.size(), before);
  times_.neighbour += omp_get_wtime() - t0;
}

// The sort moves excluded particles past size() in their previous order; those with finite
// values left the domain. Serial: only the few particles excluded by this sort are visited.
template <int D>
void Simulation<D>::record_faces(std::size_t first, std::size_t last) {
  for (std::size_t i = first; i < last; ++i) {
    const Vec<D>& x = ps_.pos[i];
    if (!x.allFinite() || !ps_.vel[i].allFinite() || !std::isfinite(ps_.rho[i])) continue;
    int face = -1;
    double beyond = 0.0;
    for (int d = 0; d < D; ++d) {
      const double below = prm_.domain_min[d] - x[d], above = x[d] - prm_.domain_max[d];
      if (below >= beyond) beyond = below, face = 2 * d;
      if (above >= beyond) beyond = above, face = 2 * d + 1;
    }
    if (face < 0) continue;  // on the boundary itself: the grid's own rounding
    const auto f = static_cast<std::size_t>(face);
    ++faces_.particles[f];
    if (faces_.first_time[f] < 0.0) faces_.first_time[f] = time_;
    faces_.last_time[f] = time_;
    if (!is_fluid(ps_.role[i])) continue;
    ++faces_.fluid[f];
    faces_.fluid_mass[f] += ps_.mass[i];
    faces_.last_id[f] = ps_.id[i];
    for (int d = 0; d < 3; ++d)
      faces_.last_pos[f][static_cast<std::size_t>(d)] = d < D ? x[d] : 0.0;
  }
}

template <int D>
void Simulation<D>::evaluate() {
  if (exchange_) {
    const double tm = omp_get_wtime();
    grid_.drop_ghosts(ps_);    // the last evaluation's halo
    grid_.wrap_periodic(ps_);  // a particle that crossed a periodic face goes to its new owner
    exchange_->migrate(ps_, steps_);
    times_.neighbour += omp_get_wtime() - tm;
  }
  sort_particles();
  if (exchange_) {
    const double th = omp_get_wtime();
    exchange_->build_halo(ps_, grid_);
    times_.neighbour += omp_get_wtime() - th;
  }
  const double t0 = omp_get_wtime();
  // Periodic images are read through the force buffers too (rare growth, amortised).
  f_.resize(ps_.stored());
  StepState<D> s = state(time_);
  for_each_hook([&](StepHook<D>& h) { h.before_forces(s); });
  // Walls' and re-initialised densities; the halo and the sort's periodic images hold the
  // sources' state already where no hook changed it.
  if (any_hook([](const StepHook<D>& h) { return h.changes_state_before_forces(); }))
    refresh_images();
  boundary_->forces(s);
  for_each_hook([&](StepHook<D>& h) { h.after_forces(s); });
  times_.interaction += omp_get_wtime() - t0;
}

template <int D>
void Simulation<D>::redistribute() {
  if (!exchange_) return;
  grid_.drop_ghosts(ps_);
  grid_.wrap_periodic(ps_);
  // acceleration() and density_rate() are stale after this (documented): the particles moved
  // and their rates did not.
  exchange_->migrate(ps_, -1);
  // Stale but sized: a second gather before the next step reads one acceleration per particle.
  f_.resize(ps_.total());
}

template <int D>
void Simulation<D>::refresh_images() {
  if (exchange_) {
    if (grid_.has_local_images()) grid_.refresh_ghosts(ps_);  // periodic images of own particles
    exchange_->refresh(ps_);  // every rank calls it, with images or not
  } else if (ps_.n_ghost > 0) {
    grid_.refresh_ghosts(ps_);
  }
}

template <int D>
void Simulation<D>::after_substep(double t) {
  StepState<D> s = state(t);
  for_each_hook([&](StepHook<D>& h) { h.prescribe(s); });
  for_each_hook([&](StepHook<D>& h) { h.finish_density(s); });
}

// dt = CFL min(dt_f, dt_cv[, dt_nu]) with dt_f = sqrt(h / max|a|) and
// dt_cv = h / (max c + max_ab h |v_ab.r_ab| / (r^2 + eta^2)) (Monaghan & Kos 1999).
template <int D>
double Simulation<D>::choose_dt() const {
  if (prm_.fixed_dt > 0.0) return prm_.fixed_dt;
  double dt = local_dt();
  return exchange_ ? exchange_->global_min(dt) : dt;
}

template <int D>
double Simulation<D>::local_dt() const {
  const long n = static_cast<long>(ps_.size());
  double a2max = 0.0;
#pragma omp parallel for schedule(static) reduction(max : a2max)
  for (long i = 0; i < n; ++i)
    if (is_fluid(ps_.role[i])) a2max = std::max(a2max, f_.ace[i].squaredNorm());
  const double h = prm_.h;
  double dt = h / (f_.cs_max + f_.visc_dt_max);
  if (a2max > 0.0) dt = std::min(dt, std::sqrt(h / std::sqrt(a2max)));
  if (prm_.viscosity == ViscosityModel::Laminar && prm_.nu > 0.0)
    dt = std::min(dt, 0.125 * h * h / prm_.nu);
  return prm_.cfl * dt;
}

template <int D>
void Simulation<D>::step() {
  if (prm_.integrator == IntegratorType::Verlet)
    step_verlet();
  else
    step_symplectic();
  {
    // Images at the integrated state, for the hooks that read them (dropped right after).
    if (any_hook([](const StepHook<D>& h) { return h.reads_images_after_integration(); }))
      refresh_images();
    StepState<D> s = state(time_ + dt_);
    for_each_hook([&](StepHook<D>& h) { h.after_integration(s); });
    grid_.drop_ghosts(ps_);  // between steps there are no periodic images
  }

  // Density bounds (fluid): excluded and counted as DualSPHysics' RhopOut.
  const double lo = prm_.rho_min_factor * prm_.rho0, hi = prm_.rho_max_factor * prm_.rho0;
  // One parallel pass counts the fluid still in the run and the fluid out of bounds (each
  // thread on the particles it integrated); the rare step with some out of bounds excludes
  // them in a serial pass.
  std::size_t out = 0, fluid_left = 0;
  auto out_of_bounds = [&](std::size_t i) {
    return std::isfinite(ps_.rho[i]) && (ps_.rho[i] < lo || ps_.rho[i] > hi);
  };
  const long n = static_cast<long>(ps_.size());
#pragma omp parallel for schedule(static) reduction(+ : out, fluid_left) \
    if (n > ParticleSet <D>::kParallelMin)
  for (long i = 0; i < n; ++i) {
    if (!is_fluid(ps_.role[i])) continue;
    if (out_of_bounds(i))
      ++out;
    else
      ++fluid_left;
  }
  if (out > 0) {  // counted again, with the exclusions
    out = fluid_left = 0;
    for (std::size_t i = 0; i < ps_.size(); ++i) {
      if (!is_fluid(ps_.role[i])) continue;
      if (out_of_bounds(i)) {
        const double ratio = ps_.rho[i] > 0.0
                                 ? std::max(ps_.rho[i] / prm_.rho0, prm_.rho0 / ps_.rho[i])
                                 : std::numeric_limits<double>::infinity();
        if (ratio > worst_rho_.ratio)
          worst_rho_ = {ratio, ps_.rho[i], time_ + dt_, ps_.id[i], ps_.pos[i]};
        ps_.pos[i].setConstant(std::numeric_limits<double>::quiet_NaN());
        ++out;
      } else {
        ++fluid_left;
      }
    }
  }
  if (out > 0) {
    sort_particles(true);
    excluded_.non_finite -= out;  // those were flagged here, not found non-finite
    excluded_.density_out_of_range += out;
  }
  time_ += dt_;
  ++steps_;
  if (first_dt_ == 0.0) first_dt_ = dt_;
  if (!(dt_ > prm_.dt_collapse_factor * first_dt_)) {
    // Name the fluid particle with the largest acceleration (only when stopping).
    std::size_t worst = ps_.size();
    double a2 = -1.0;
    for (std::size_t i = 0; i < ps_.size(); ++i)
      if (is_fluid(ps_.role[i]) && f_.ace[i].squaredNorm() > a2)
        a2 = f_.ace[i].squaredNorm(), worst = i;
    std::ostringstream msg;
    msg << "time step collapsed to " << dt_ << " s at t = " << time_ << " s (step " << steps_
        << ", first dt " << first_dt_
        << " s, limit watchdog.dt_collapse = " << prm_.dt_collapse_factor << " of it)";
    if (worst < ps_.size()) {
      msg << "; largest acceleration " << std::sqrt(a2) << " m/s^2 on fluid particle "
          << ps_.id[worst] << " at (";
      for (int d = 0; d < D; ++d) msg << (d ? ", " : "") << ps_.pos[worst][d];
      msg << ") m";
    }
    msg << ". Likely cause: particles pressed together (a violent impact or an initial overlap) "
           "drive the forces up; lower time.cfl, raise physics.coefsound, or check the geometry "
           "for fluid placed inside walls";
    throw InstabilityError(msg.str());
  }
  if (exchange_) fluid_left = exchange_->global_sum(fluid_left);
  if (fluid_left == 0) throw InstabilityError("every fluid particle has been excluded");
}

// Symplectic position-Verlet predictor-corrector as in DualSPHysics (Leimkuhler 1996):
// half step with forces at n, full step with forces at n+1/2; density by the
// rho^{n+1} = rho^n (2 - eps)/(2 + eps), eps = -(drho/rho)^{n+1/2} dt update. Every role
// integrates its density; only fluid integrates positions and velocities (moving walls take
// theirs from the prescribe stage at t + dt/2 and t + dt).
template <int D>
void Simulation<D>::step_symplectic() {
  evaluate();
  dt_ = choose_dt();
  const double t0 = omp_get_wtime();
  const long n = static_cast<long>(ps_.size());
  const double half = 0.5 * dt_;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    ps_.vel_prev[i] = ps_.vel[i];
    ps_.rho_prev[i] = ps_.rho[i];
    ps_.rho[i] = static_cast<StateReal>(ps_.rho[i] + half * f_.drho[i]);
    if (is_fluid(ps_.role[i])) {
      const Vec<D> v = widen<D>(ps_.vel[i]);
      ps_.pos[i] += half * v;
      ps_.vel[i] = narrow<D>(v + half * f_.ace[i]);
    }
  }
  after_substep(time_ + half);
  times_.integration += omp_get_wtime() - t0;

  evaluate();
  const double t1 = omp_get_wtime();
  const long m = static_cast<long>(ps_.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < m; ++i) {
    const double eps = -f_.drho[i] / ps_.rho[i] * dt_;
    ps_.rho[i] = static_cast<StateReal>(ps_.rho_prev[i] * (2.0 - eps) / (2.0 + eps));
    if (is_fluid(ps_.role[i])) {
      ps_.vel[i] = narrow<D>(widen<D>(ps_.vel_prev[i]) + dt_ * f_.ace[i]);
      ps_.pos[i] += half * widen<D>(ps_.vel[i]);  // the stored (rounded) velocity
    }
  }
  after_substep(time_ + dt_);
  times_.integration += omp_get_wtime() - t1;
}

// Verlet (Monaghan 1989) with an Euler step every verlet_steps steps to keep the two
// interleaved solutions together, as in DualSPHysics.
template <int D>
void Simulation<D>::step_verlet() {
  evaluate();
  dt_ = choose_dt();
  const double t0 = omp_get_wtime();
  const bool euler = ++verlet_counter_ >= prm_.verlet_steps;
  if (euler) verlet_counter_ = 0;
  const long n = static_cast<long>(ps_.size());
  const double dt = dt_, dt2 = dt_ * dt_;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const double rho_new = euler ? double(ps_.rho[i]) + dt * f_.drho[i]
                                 : double(ps_.rho_prev[i]) + 2.0 * dt * f_.drho[i];
    ps_.rho_prev[i] = ps_.rho[i];
    ps_.rho[i] = static_cast<StateReal>(rho_new);
    if (is_fluid(ps_.role[i])) {
      const Vec<D> v = widen<D>(ps_.vel[i]);
      const Vec<D> v_new = euler ? Vec<D>(v + dt * f_.ace[i])
                                 : Vec<D>(widen<D>(ps_.vel_prev[i]) + 2.0 * dt * f_.ace[i]);
      ps_.pos[i] += dt * v + 0.5 * dt2 * f_.ace[i];
      ps_.vel_prev[i] = ps_.vel[i];
      ps_.vel[i] = narrow<D>(v_new);
    }
  }
  after_substep(time_ + dt_);
  times_.integration += omp_get_wtime() - t0;
}

template <int D>
const std::vector<double>& Simulation<D>::pressure() {
  // Written into the P/rho^2 buffer: between steps nothing reads it (the next evaluation
  // recomputes it), so output costs no array of its own.
  const std::size_t n = ps_.total();
  f_.prs.resize(n);
  for (std::size_t i = 0; i < n; ++i) f_.prs[i] = eos_.pressure(ps_.rho[i]);
  return f_.prs;
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace swell
