// Damping zones and the settling phase (bc/damping.hpp).
#include "bc/damping.hpp"

#include <stdexcept>

namespace swell {

namespace {

std::string zone_label(const DampingZone& z) {
  return "damping zone '" + z.name + "'";
}

}  // namespace

void check_damping_zone(const DampingZone& z, int dim) {
  const std::string who = zone_label(z);
  const Eigen::Vector3d n =
      dim == 2 ? Eigen::Vector3d(z.direction.x(), z.direction.y(), 0.0) : z.direction;
  if (!(n.norm() > 0.0) || !n.allFinite())
    throw std::invalid_argument(who + ": the direction must be a non-zero vector");
  if (!(z.rate > 0.0) || !std::isfinite(z.rate))
    throw std::invalid_argument(who + ": the rate must be a number > 0 [1/s]");
  if (z.shape == DampingZone::Shape::Plane) {
    if (!(z.length > 0.0) || !std::isfinite(z.length))
      throw std::invalid_argument(who + ": the length must be a number > 0 [m]");
  } else {
    for (int d = 0; d < dim; ++d)
      if (!(z.box_min[d] < z.box_max[d]))
        throw std::invalid_argument(who + ": the box needs min < max on every axis");
  }
  bool any = false;
  for (int d = 0; d < dim; ++d) any = any || z.components[static_cast<std::size_t>(d)];
  if (!any) throw std::invalid_argument(who + ": it damps no velocity component");
  if (!(z.stop > z.start)) throw std::invalid_argument(who + ": stop must be later than start");
}

DampingGeometry damping_geometry(const DampingZone& z, int dim) {
  DampingGeometry g;
  g.n = z.direction;
  if (dim == 2) g.n.z() = 0.0;
  g.n.normalize();
  if (z.shape == DampingZone::Shape::Plane) {
    g.origin = z.at;
    g.length = z.length;
  } else {
    // s = 0 at the box's corner furthest against n, 1 at the opposite corner.
    g.box = true;
    g.lo = z.box_min;
    g.hi = z.box_max;
    g.length = 0.0;
    for (int d = 0; d < dim; ++d) {
      g.origin[d] = g.n[d] >= 0.0 ? z.box_min[d] : z.box_max[d];
      g.length += std::abs(g.n[d]) * (z.box_max[d] - z.box_min[d]);
    }
  }
  if (dim == 2) g.origin.z() = g.lo.z() = g.hi.z() = 0.0;
  g.inv_length = 1.0 / g.length;
  return g;
}

template <int D>
DampingZones<D>::DampingZones(std::vector<DampingZone> zones) : zones_(std::move(zones)) {
  for (const DampingZone& z : zones_) {
    check_damping_zone(z, D);
    geometry_.push_back(damping_geometry(z, D));
    Vec<D> m;
    for (int d = 0; d < D; ++d) m[d] = z.components[static_cast<std::size_t>(d)] ? 1.0 : 0.0;
    mask_.push_back(m);
  }
  active_.reserve(zones_.size());
}

// One pass over the particles; each particle's factor depends on its own position only, so
// the result is the same for any thread count and schedule. A component's factor is
// g = exp(-sigma dt) where damped and exactly 1 where not (v * 1 == v bitwise).
template <int D>
void DampingZones<D>::after_integration(StepState<D>& s) {
  const double t_mid = s.time - 0.5 * s.dt, dt = s.dt;
  active_.clear();  // no allocation: the capacity was reserved for every zone
  for (std::size_t k = 0; k < zones_.size(); ++k)
    if (t_mid >= zones_[k].start && t_mid < zones_[k].stop) active_.push_back(k);
  if (active_.empty() || !(dt > 0.0)) return;
  ParticleSet<D>& ps = s.particles;
  const bool verlet = s.params.integrator == IntegratorType::Verlet;
  const long n = static_cast<long>(ps.size());
  const std::size_t* active = active_.data();
  const std::size_t na = active_.size();
#pragma omp parallel for schedule(static) if (n > ParticleSet <D>::kParallelMin)
  for (long i = 0; i < n; ++i) {
    if (!is_fluid(ps.role[i])) continue;
    Vec<D> f = Vec<D>::Ones();
    bool damped = false;
    for (std::size_t a = 0; a < na; ++a) {
      const std::size_t k = active[a];
      const double depth = damping_depth<D>(geometry_[k], ps.pos[i]);
      if (depth <= 0.0) continue;  // outside, or at the start (r(0) = 0)
      const double g = std::exp(-zones_[k].rate * damping_ramp(zones_[k].ramp, depth) * dt);
      for (int d = 0; d < D; ++d)
        if (mask_[k][d] != 0.0) f[d] *= g;
      damped = true;
    }
    if (!damped) continue;
    ps.vel[i] = narrow<D>(widen<D>(ps.vel[i]).cwiseProduct(f));
    if (verlet) ps.vel_prev[i] = narrow<D>(widen<D>(ps.vel_prev[i]).cwiseProduct(f));
  }
}

template <int D>
Settling<D>::Settling(const SettlingSpec& spec) : spec_(spec) {
  if (!(spec_.duration > 0.0) || !std::isfinite(spec_.duration))
    throw std::invalid_argument("settling: the duration must be a number > 0 [s]");
  if (!(spec_.rate > 0.0) || !std::isfinite(spec_.rate))
    throw std::invalid_argument("settling: the rate must be a number > 0 [1/s]");
}

// The step covers [time - dt, time]; its factor is exp(-integral of sigma over it).
template <int D>
void Settling<D>::after_integration(StepState<D>& s) {
  const double t0 = s.time - s.dt;
  if (t0 >= spec_.duration || !(s.dt > 0.0)) return;
  const double g = std::exp(-settling_integral(spec_, t0, s.time));
  ParticleSet<D>& ps = s.particles;
  const bool verlet = s.params.integrator == IntegratorType::Verlet;
  const long n = static_cast<long>(ps.size());
#pragma omp parallel for schedule(static) if (n > ParticleSet <D>::kParallelMin)
  for (long i = 0; i < n; ++i) {
    if (!is_fluid(ps.role[i])) continue;
    ps.vel[i] = narrow<D>(g * widen<D>(ps.vel[i]));
    if (verlet) ps.vel_prev[i] = narrow<D>(g * widen<D>(ps.vel_prev[i]));
  }
}

template class DampingZones<2>;
template class DampingZones<3>;
template class Settling<2>;
template class Settling<3>;

}  // namespace swell
