#include "validation/wave_theory.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "case/geometry.hpp"
#include "waves/dispersion.hpp"
#include "waves/wavemaker.hpp"

namespace swell {

Series paddle_theory_series(const CaseSpec& spec, const std::string& gauge, double dt,
                            double t_end) {
  const GaugeSpec* g = nullptr;
  for (const auto& s : spec.gauges)
    if (s.name == gauge) g = &s;
  if (!g) throw std::invalid_argument("theory reference: the case has no gauge '" + gauge + "'");
  if (g->kind != GaugeSpec::Kind::Height)
    throw std::invalid_argument("theory reference: gauge '" + gauge +
                                "' is not a height gauge (the paddle theory gives the level)");
  std::size_t paddle = spec.bodies.size();
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    const MotionSpec& m = spec.bodies[i].motion;
    if (m.type != MotionSpec::Type::Wave || !m.paddle) continue;
    if (paddle != spec.bodies.size())
      throw std::invalid_argument("theory reference: the case has two wave paddles (" +
                                  spec.bodies[paddle].name + ", " + spec.bodies[i].name + ")");
    paddle = i;
  }
  if (paddle == spec.bodies.size())
    throw std::invalid_argument("theory reference: the case has no wave paddle (type: wave)");
  if (!(dt > 0.0) || !(t_end > 0.0))
    throw std::invalid_argument("theory reference: expected a sampling interval and end > 0");

  const MotionSpec& m = spec.bodies[paddle].motion;
  const waves::PaddleSignal& sig = *m.paddle;
  const auto geo = case_geometry(spec);
  const double x0 = geo[paddle].shape->bounds().max[0];  // the fluid-side face at rest
  const double x = g->at[0] - x0;
  const double depth = sig.paddle.depth, swl = m.bed + depth;
  const double grav = spec.gravity.norm();
  // Front: the peak component's group velocity (a solitary wave: its celerity sqrt(g (d + H))).
  double speed = std::sqrt(grav * depth);
  if (sig.solitary) {
    speed = sig.soliton.celerity;
  } else if (sig.peak_omega() > 0.0) {
    speed = waves::group_speed(sig.peak_omega(), depth, grav);
  }
  const double arrival = x / speed;
  const auto ramp = [&](double tau) {  // bc/motion.hpp's smoothstep ramp
    if (m.ramp <= 0.0) return tau >= 0.0 ? 1.0 : 0.0;
    const double s = std::clamp(tau / m.ramp, 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
  };

  Series s;
  s.name = gauge;
  s.unit = "m";
  const auto n = static_cast<std::size_t>(std::floor(t_end / dt + 1e-9)) + 1;
  s.t.reserve(n);
  s.v.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt, tau = t - m.start;
    // A solitary wave is its own front (the soliton is ~0 ahead of it); periodic waves ramp in
    // as the paddle did, delayed by the travel time.
    const double f = sig.solitary ? (tau >= 0.0 ? 1.0 : 0.0) : ramp(tau - arrival);
    s.t.push_back(t);
    s.v.push_back(swl + f * sig.elevation(tau, x));
  }
  return s;
}

}  // namespace swell
