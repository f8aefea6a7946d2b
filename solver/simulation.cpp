#include "solver/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace swell {

template <int D>
Simulation<D>::Simulation(const SolverParams& params, ParticleSet<D> particles)
    : prm_(params), eos_(params.rho0, params.c0, params.gamma), ps_(std::move(particles)) {
  if (!(prm_.h > 0.0) || !(prm_.c0 > 0.0) || !(prm_.dp > 0.0))
    throw std::invalid_argument("Simulation: h, c0 and dp must be positive");
  const double support = kernel_support_factor(prm_.kernel) * prm_.h;
  grid_ =
      CellGrid<D>(prm_.domain_min.template head<D>(), prm_.domain_max.template head<D>(), support);
  f_.resize(ps_.total());
  // Forces at the initial state, so acceleration() (wall loads) is valid before the first step.
  evaluate();
}

template <int D>
std::size_t Simulation<D>::fluid_count() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < ps_.size(); ++i) n += ps_.kind[i] == Kind::Fluid;
  return n;
}

template <int D>
void Simulation<D>::sort_particles() {
  const double t0 = omp_get_wtime();
  const auto r = grid_.sort(ps_);
  excluded_.out_of_domain += r.out_of_domain;
  excluded_.non_finite += r.non_finite;
  times_.neighbour += omp_get_wtime() - t0;
}

template <int D>
void Simulation<D>::evaluate() {
  sort_particles();
  const double t0 = omp_get_wtime();
  compute_pressure(ps_, eos_, f_);
  with_kernel<D>(prm_.kernel, prm_.h, [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    if (prm_.viscosity == ViscosityModel::Artificial)
      interact<D, K, ViscosityModel::Artificial>(ps_, grid_, kernel, prm_, f_);
    else
      interact<D, K, ViscosityModel::Laminar>(ps_, grid_, kernel, prm_, f_);
    return 0;
  });
  times_.interaction += omp_get_wtime() - t0;
}

// dt = CFL min(dt_f, dt_cv[, dt_nu]) with dt_f = sqrt(h / max|a|) and
// dt_cv = h / (max c + max_ab h |v_ab.r_ab| / (r^2 + eta^2)) (Monaghan & Kos 1999).
template <int D>
double Simulation<D>::choose_dt() const {
  const long n = static_cast<long>(ps_.size());
  double a2max = 0.0;
#pragma omp parallel for schedule(static) reduction(max : a2max)
  for (long i = 0; i < n; ++i)
    if (ps_.kind[i] == Kind::Fluid) a2max = std::max(a2max, f_.ace[i].squaredNorm());
  const double h = prm_.h;
  double dt = h / (f_.cs_max + f_.visc_dt_max);
  if (a2max > 0.0) dt = std::min(dt, std::sqrt(h / std::sqrt(a2max)));
  if (prm_.viscosity == ViscosityModel::Laminar && prm_.nu > 0.0)
    dt = std::min(dt, 0.125 * h * h / prm_.nu);
  return prm_.cfl * dt;
}

// DBC: the density of a wall particle never drops below rho0, so walls never pull fluid in.
template <int D>
void Simulation<D>::finish_density(std::size_t i) {
  if (ps_.kind[i] == Kind::Boundary) {
    if (ps_.rho[i] < prm_.rho0) ps_.rho[i] = prm_.rho0;
  }
}

template <int D>
void Simulation<D>::step() {
  if (prm_.integrator == IntegratorType::Verlet)
    step_verlet();
  else
    step_symplectic();

  // Density bounds (fluid): excluded and counted as DualSPHysics' RhopOut.
  const double lo = prm_.rho_min_factor * prm_.rho0, hi = prm_.rho_max_factor * prm_.rho0;
  // One pass also counts the fluid still in the run (no second O(N) scan per step).
  std::size_t out = 0, fluid_left = 0;
  for (std::size_t i = 0; i < ps_.size(); ++i) {
    if (ps_.kind[i] != Kind::Fluid) continue;
    if (std::isfinite(ps_.rho[i]) && (ps_.rho[i] < lo || ps_.rho[i] > hi)) {
      ps_.pos[i].setConstant(std::numeric_limits<double>::quiet_NaN());
      ++out;
    } else {
      ++fluid_left;
    }
  }
  if (out > 0) {
    sort_particles();
    excluded_.non_finite -= out;  // those were flagged here, not found non-finite
    excluded_.density_out_of_range += out;
  }
  time_ += dt_;
  ++steps_;
  if (first_dt_ == 0.0) first_dt_ = dt_;
  if (!(dt_ > prm_.dt_collapse_factor * first_dt_)) {
    std::ostringstream msg;
    msg << "time step collapsed to " << dt_ << " s at t = " << time_ << " s (step " << steps_
        << ", first dt " << first_dt_ << " s): the run is unstable";
    throw InstabilityError(msg.str());
  }
  if (fluid_left == 0) throw InstabilityError("every fluid particle has been excluded");
}

// Symplectic position-Verlet predictor-corrector as in DualSPHysics (Leimkuhler 1996):
// half step with forces at n, full step with forces at n+1/2; density by the
// rho^{n+1} = rho^n (2 - eps)/(2 + eps), eps = -(drho/rho)^{n+1/2} dt update.
template <int D>
void Simulation<D>::step_symplectic() {
  evaluate();
  dt_ = choose_dt();
  const double t0 = omp_get_wtime();
  const long n = static_cast<long>(ps_.size());
  const double half = 0.5 * dt_;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    ps_.pos0[i] = ps_.pos[i];
    ps_.vel0[i] = ps_.vel[i];
    ps_.rho0[i] = ps_.rho[i];
    ps_.rho[i] += half * f_.drho[i];
    if (ps_.kind[i] == Kind::Fluid) {
      ps_.pos[i] += half * ps_.vel[i];
      ps_.vel[i] += half * f_.ace[i];
    }
    finish_density(i);
  }
  times_.integration += omp_get_wtime() - t0;

  evaluate();
  const double t1 = omp_get_wtime();
  const long m = static_cast<long>(ps_.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < m; ++i) {
    const double eps = -f_.drho[i] / ps_.rho[i] * dt_;
    ps_.rho[i] = ps_.rho0[i] * (2.0 - eps) / (2.0 + eps);
    if (ps_.kind[i] == Kind::Fluid) {
      ps_.vel[i] = ps_.vel0[i] + dt_ * f_.ace[i];
      ps_.pos[i] += half * ps_.vel[i];
    }
    finish_density(i);
  }
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
    const double rho_new =
        euler ? ps_.rho[i] + dt * f_.drho[i] : ps_.rho0[i] + 2.0 * dt * f_.drho[i];
    ps_.rho0[i] = ps_.rho[i];
    ps_.rho[i] = rho_new;
    if (ps_.kind[i] == Kind::Fluid) {
      const Vec<D> v_new =
          euler ? Vec<D>(ps_.vel[i] + dt * f_.ace[i]) : Vec<D>(ps_.vel0[i] + 2.0 * dt * f_.ace[i]);
      ps_.pos[i] += dt * ps_.vel[i] + 0.5 * dt2 * f_.ace[i];
      ps_.vel0[i] = ps_.vel[i];
      ps_.vel[i] = v_new;
    }
    finish_density(i);
  }
  times_.integration += omp_get_wtime() - t0;
}

template <int D>
const std::vector<double>& Simulation<D>::pressure() {
  const std::size_t n = ps_.size();
  f_.press.resize(ps_.total());
  for (std::size_t i = 0; i < n; ++i) f_.press[i] = eos_.pressure(ps_.rho[i]);
  return f_.press;
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace swell
