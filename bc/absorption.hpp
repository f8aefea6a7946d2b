// Active wave absorption at a piston paddle (AWAS): the paddle's velocity is corrected from the
// surface elevation measured in front of it, so that a wave coming back to the paddle (reflected
// by a structure or the flume's end) is absorbed instead of being re-reflected.
//
// Method (Schaffer & Klopman 2000, J. Waterway Port Coastal Ocean Eng. 126(2):88-97; in SPH,
// Altomare et al. 2017, Coastal Eng. 127:37-54). In front of the paddle the elevation is the sum
// of the wave going out, eta_out, and the wave coming in, eta_in; a piston moving with velocity
// U sends out eta_out = (F / w) U + eta_in (it radiates, and it reflects what comes in as a wall
// does), F = H / S the Biesel transfer function. For eta_out to be the target eta_T the paddle
// must move with U = (w / F) (eta_T - eta_in), and with eta_in = eta_M - eta_T from the measured
// eta_M this is the target velocity plus the correction
//     U_c = G (eta_T - eta_M),   G = w / F(kd)   (tuned)   or   G = sqrt(g / d)   (shallow),
// the shallow-water limit of w / F (F -> kd). The tuned gain is exact at the target's peak
// frequency w_p (a regular wave's frequency, Tp of a spectrum) and the shallow gain at long
// waves; S&K's frequency-dependent filter is approximated by this constant gain, so waves far
// from w_p are absorbed less well (the absorbed fraction is measured in the tests and
// docs/method/boundaries.md#active-absorption-at-a-piston).
//
// Filters (the "documented filter" of the issue), with T_ref the target's peak period (a
// solitary wave: Goring's duration):
//  - the error e = eta_M - eta_T is smoothed by a first-order low-pass filter of time constant
//    tau_f (default 0.02 T_ref: phase lag atan(w tau_f) = 7 degrees at w_p, gain loss 0.8 %),
//    which removes the step-to-step noise of the SPH water level;
//  - the correction displacement X_c is pulled back to zero with time constant tau_d (default
//    10 T_ref): dX_c/dt = U_c - X_c / tau_d, so a mean set-down or a slow error cannot make the
//    paddle drift away.
// The measuring line is vertical, `distance` in front of the paddle's face (default: one kernel
// support, where the kernel no longer reaches the paddle's particles), and moves with the
// paddle; eta_T is the target wave there (its linear components and Stokes' bound harmonic, see
// waves::PaddleSignal::elevation; the ramp of the motion law scales it). Measuring at a
// distance x_m advances the incoming wave by x_m / c, which the filter's delay ~tau_f partly
// cancels.
//
// Time stepping: the error is measured once per step, after the integration (t_n+1), and the
// correction velocity is held constant over the next step; the paddle's position adds
// X_c(t_n) + V_c (t - t_n) at every substep, so it is continuous and its velocity is the exact
// derivative. The state (X_c, V_c, filtered error, t_n) is saved in the checkpoint: a restart
// continues bitwise. Absorption acts from the motion's start to its stop.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "bc/motion.hpp"
#include "solver/gauges.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/time/exchange.hpp"

namespace swell {

class PaddleAbsorber {
 public:
  PaddleAbsorber() = default;
  // spec must be a Wave motion with absorption, on a piston.
  explicit PaddleAbsorber(const MotionSpec& spec) : spec_(spec) {
    const waves::PaddleSignal& s = *spec.paddle;
    const double d = s.paddle.depth;
    const MotionSpec::Absorption& a = *spec.absorption;
    const double omega = s.peak_omega();
    if (a.gain == MotionSpec::Absorption::Gain::Tuned && omega > 0.0) {
      const double k = waves::wave_number(omega, d, spec.g);
      gain_ = omega / waves::transfer_function(s.paddle, k);
    } else {
      gain_ = std::sqrt(spec.g / d);
    }
    const double t_ref = omega > 0.0 ? 2.0 * std::numbers::pi / omega : s.shortest_period();
    filter_ = a.filter ? *a.filter : 0.02 * t_ref;
    drift_ = a.drift ? *a.drift : 10.0 * t_ref;
  }

  double gain() const { return gain_; }
  double filter_time() const { return filter_; }
  double drift_time() const { return drift_; }
  double correction() const { return x_c_; }
  double max_correction() const { return max_abs_; }

  // The correction displacement and velocity at time t (in [t_n, t_n+1] during a step).
  double offset(double t) const { return x_c_ + v_c_ * (t - t_n_); }
  double velocity() const { return v_c_; }

  // Once per step after the integration, at time t with step dt: measures the water level in
  // front of the paddle, whose target displacement (ramped) is x_target, and updates the state.
  // `ex` (several ranks): the paddle's position and the water level are reduced over the ranks.
  template <int D>
  void update(const ParticleSet<D>& ps, const SolverParams& p, double t, double dt, double x_target,
              const Exchange<D>* ex = nullptr) {
    if (!placed_) locate(ps, p, ex);
    const double tau = t - spec_.start;
    if (tau <= 0.0 || t > spec_.stop) {  // not active: hold the correction still
      x_c_ = offset(t);
      v_c_ = 0.0;
      t_n_ = t;
      return;
    }
    const int up = D - 1;
    const double distance = spec_.absorption->distance ? *spec_.absorption->distance : support_;
    const double along = face_ + x_target + offset(t) + distance;  // along `direction`
    Vec<D> base = Vec<D>::Zero();
    for (int k = 0; k < D; ++k) base[k] = lateral_[k] + along * spec_.direction[k];
    base[up] = spec_.bed;
    const double depth = spec_.paddle->paddle.depth;
    const double level = with_kernel<D>(p.kernel, p.h, [&](const auto& kernel) {
      if (!ex)
        return water_height(ps, kernel, base, up, spec_.bed + 2.0 * depth, 0.5 * p.dp, p.rho0);
      const auto sum = [ex](std::vector<double>& v) { ex->global_sum_in_place(v); };
      return water_height(ps, kernel, base, up, spec_.bed + 2.0 * depth, 0.5 * p.dp, p.rho0, 0.5,
                          &sum);
    });
    eta_measured_ = level - (spec_.bed + depth);
    // The motion law's smoothstep ramp (bc/motion.hpp) scales the target wave too.
    double ramp = 1.0;
    if (spec_.ramp > 0.0 && tau < spec_.ramp) {
      const double s = tau / spec_.ramp;
      ramp = s * s * (3.0 - 2.0 * s);
    }
    eta_target_ = ramp * spec_.paddle->elevation(tau, distance);
    const double e = eta_measured_ - eta_target_;
    if (!started_) {
      error_ = e;
      started_ = true;
    } else {
      error_ += (filter_ > 0.0 ? -std::expm1(-dt / filter_) : 1.0) * (e - error_);
    }
    x_c_ = offset(t);
    t_n_ = t;
    v_c_ = -gain_ * error_ - x_c_ / drift_;
    max_abs_ = std::max(max_abs_, std::abs(x_c_));
  }

  double eta_measured() const { return eta_measured_; }
  double eta_target() const { return eta_target_; }

  void save(std::map<std::string, double>& out, const std::string& k) const {
    out[k + "awas.x"] = x_c_;
    out[k + "awas.v"] = v_c_;
    out[k + "awas.t"] = t_n_;
    out[k + "awas.error"] = error_;
    out[k + "awas.started"] = started_ ? 1.0 : 0.0;
    out[k + "awas.max"] = max_abs_;
  }
  // False if the entries are missing (a checkpoint of a run without absorption).
  bool restore(const std::map<std::string, double>& in, const std::string& k) {
    const auto get = [&](const char* name, double& v) {
      const auto it = in.find(k + name);
      if (it == in.end()) return false;
      v = it->second;
      return true;
    };
    double started = 0.0;
    return get("awas.x", x_c_) && get("awas.v", v_c_) && get("awas.t", t_n_) &&
           get("awas.error", error_) && get("awas.started", started) && get("awas.max", max_abs_) &&
           ((started_ = started != 0.0), true);
  }

 private:
  // The paddle's face at rest: the furthest of its particles along `direction` plus dp / 2; in
  // 3D the line is at the mean lateral position of the paddle's particles.
  template <int D>
  void locate(const ParticleSet<D>& ps, const SolverParams& p, const Exchange<D>* ex) {
    double far = -1e300;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::size_t n = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.role[i] != Role::MovingWall || ps.body[i] != body_) continue;
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      x.template head<D>() = ps.pos_ref[i];
      far = std::max(far, x.dot(spec_.direction));
      sum += x;
      ++n;
    }
    if (ex) {  // several ranks: the paddle's particles on every rank
      far = ex->global_max(far);
      std::vector<double> s4{sum.x(), sum.y(), sum.z(), static_cast<double>(n)};
      ex->global_sum_in_place(s4);
      sum = Eigen::Vector3d(s4[0], s4[1], s4[2]);
      n = static_cast<std::size_t>(s4[3]);
    }
    if (n == 0) far = 0.0;
    face_ = far + 0.5 * p.dp;
    const Eigen::Vector3d mean = n > 0 ? Eigen::Vector3d(sum / double(n)) : sum;
    lateral_ = mean - mean.dot(spec_.direction) * spec_.direction;
    lateral_[D - 1] = 0.0;
    support_ = kernel_support_factor(p.kernel) * p.h;
    placed_ = true;
  }

 public:
  std::size_t body_ = 0;  // the paddle's body id (set by MovingBodies)

 private:
  MotionSpec spec_{};
  double gain_ = 0.0, filter_ = 0.0, drift_ = 0.0;
  double x_c_ = 0.0, v_c_ = 0.0, t_n_ = 0.0, error_ = 0.0, max_abs_ = 0.0;
  double eta_measured_ = 0.0, eta_target_ = 0.0;
  bool started_ = false, placed_ = false;
  double face_ = 0.0, support_ = 0.0;
  Eigen::Vector3d lateral_ = Eigen::Vector3d::Zero();
};

}  // namespace swell
