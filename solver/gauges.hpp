// Point measurements on a particle set: pressure and velocity probes, free-surface elevation
// and the fluid load on a boundary body.
//
// Every gauge is a plain function of a ParticleSet plus the per-particle arrays it needs
// (pressure, acceleration), so the same code serves a running Simulation (particles(),
// pressure(), acceleration()) and post-processing of a snapshot read from file. The neighbour
// search is brute force over the active particles with a cheap per-axis prefilter: the cell
// order of the particles can be stale between steps, and a scan gives the same answer whatever
// the particle order (up to floating-point summation order).
//
// Interpolating gauges use fluid particles only, with volume V_j = m_j / rho_j, and are
// templated on the kernel type (a kernel object of solver/kernels.hpp, e.g. from with_kernel).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross(), unitOrthogonal()
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "solver/state/particle_set.hpp"

namespace swell {

namespace gauge_detail {

// Calls fn(j, r) for every active fluid particle j with r = |x - x_j| < support.
template <int D, class Fn>
void for_fluid_near(const ParticleSet<D>& ps, const Vec<D>& x, double support, Fn&& fn) {
  const double s2 = support * support;
  for (std::size_t j = 0; j < ps.size(); ++j) {
    if (ps.role[j] != Role::Fluid) continue;
    const Vec<D> d = x - ps.pos[j];
    if (d.cwiseAbs().maxCoeff() >= support) continue;  // cheap box test first
    const double r2 = d.squaredNorm();
    if (r2 < s2) fn(j, std::sqrt(r2));
  }
}

// The arguments of a water-level line, checked before anything indexes x_base with `up`.
template <int D>
void check_line(const Vec<D>& x_base, int up, double z_top, double dz) {
  if (up < 0 || up >= D) throw std::invalid_argument("water_height: up axis out of range");
  if (!(dz > 0.0)) throw std::invalid_argument("water_height: dz must be positive");
  if (!(z_top > x_base[up]))
    throw std::invalid_argument("water_height: z_top must lie above the start of the line");
}

// The particles with keep(j) whose horizontal distance to the vertical line through x_base is
// below the support (the candidates of a water-level line; check_line first). The list is a
// per-thread buffer reused by the next call (no allocation once it has grown: wave gauges with
// `sampling: mean` run this every step); use it before calling again.
template <int D, class Keep>
const std::vector<std::uint32_t>& line_candidates(const ParticleSet<D>& ps, const Vec<D>& x_base,
                                                  int up, double support, Keep&& keep) {
  static thread_local std::vector<std::uint32_t> near;
  near.clear();
  for (std::size_t j = 0; j < ps.size(); ++j) {
    if (!keep(j)) continue;
    double h2 = 0.0;
    for (int d = 0; d < D; ++d) {
      if (d == up) continue;
      const double e = ps.pos[j][d] - x_base[d];
      h2 += e * e;
    }
    if (h2 < support * support) near.push_back(static_cast<std::uint32_t>(j));
  }
  return near;
}

// sum_j m_j W(x - x_j) over the candidates.
template <int D, class K>
double mass_sum(const ParticleSet<D>& ps, const K& kernel, const std::vector<std::uint32_t>& near,
                const Vec<D>& x) {
  const double s2 = kernel.support() * kernel.support();
  double sum = 0.0;
  for (const std::uint32_t j : near) {
    const double r2 = (x - ps.pos[j]).squaredNorm();
    if (r2 < s2) sum += ps.mass[j] * kernel.w(std::sqrt(r2));
  }
  return sum;
}

}  // namespace gauge_detail

// Pressure at point x: the Shepard-normalised kernel interpolation over fluid particles
//   p(x) = sum_j p_j W(x - x_j) V_j / sum_j W(x - x_j) V_j,   V_j = m_j / rho_j,
// as DualSPHysics' MeasureTool computes values at points (Shepard 1968 correction). The
// normalisation removes the kernel truncation at free surfaces and walls (only fluid is
// summed), so a probe near a wall is not biased low; it reproduces constant fields exactly.
// `pressure` is indexed as ps (ps.size() entries at least). Returns NaN when no fluid particle
// lies within the kernel support of x (a dry point). For a wall pressure sensor, probe at
// x_wall + h n (n the unit normal into the fluid), as DualSPHysics' pressure gauges do.
template <int D, class K>
double probe_pressure(const ParticleSet<D>& ps, const std::vector<double>& pressure,
                      const K& kernel, const Vec<D>& x) {
  if (pressure.size() < ps.size())
    throw std::invalid_argument("probe_pressure: pressure array shorter than the particle set");
  double sum_p = 0.0, sum_w = 0.0;
  gauge_detail::for_fluid_near(ps, x, kernel.support(), [&](std::size_t j, double r) {
    const double wv = kernel.w(r) * ps.mass[j] / ps.rho[j];
    sum_p += pressure[j] * wv;
    sum_w += wv;
  });
  if (!(sum_w > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return sum_p / sum_w;
}

// Quadrature points of a sensor face centred at c with unit normal n: a segment of length
// `size` across n (2D) or a disc of diameter `size` (3D), points about dp/2 apart (at least 4 a
// side in 2D, the centre if the disc is smaller than the spacing).
template <int D>
std::vector<Vec<D>> face_points(const Vec<D>& c, const Vec<D>& n, double size, double dp) {
  std::vector<Vec<D>> pts;
  const int k = std::max(4, static_cast<int>(std::ceil(size / (0.5 * dp))));
  if constexpr (D == 2) {
    const Vec<D> t(-n.y(), n.x());
    for (int i = 0; i < k; ++i) pts.push_back(c + (-0.5 + (i + 0.5) / k) * size * t);
  } else {
    const Vec<D> t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    const double r = 0.5 * size;
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        const double u = (-0.5 + (i + 0.5) / k) * size, v = (-0.5 + (j + 0.5) / k) * size;
        if (u * u + v * v <= r * r) pts.push_back(c + u * t1 + v * t2);
      }
    if (pts.empty()) pts.push_back(c);
  }
  return pts;
}

// Pressure on a sensor face: at each face point x_s, the fluid pressure at q = x_s + offset n
// (the Shepard ratio p_S(q) of probe_pressure, fluid particles only) extrapolated back to the
// wall hydrostatically and weighted by the point's wetness w,
//   p(x_s) = w [p_S(q) - rho0 offset g . n],
// then averaged over the face, points with no fluid in reach counting 0, as a transducer reads
// air. The weight tells a point above the water from one under it:
//   w = min(1, sum_j W(q - x_j) V_j / (1/2))  where the fluid's kernel centroid lies below q
//       (along g), the sum over fluid and wall particles;   w = 1 otherwise.
// Above the water the fluid lies below the point and fills less than the half of the kernel it
// fills at a flat free surface, and the plain Shepard ratio would carry the surface particles'
// pressure up to a kernel support above the water (the caisson's face 2-4 cm above the still
// water read 71 Pa in still water): w fades such points to 0 continuously, a wall beside them
// adding little (its particles lie at least offset + dp/2 from q). Under water the kernel sum
// can fall below 1/2 too, in a wall corner whose fluid is held off both walls (DBC's 1.5 dp
// gap after a surge: 0.4 at Lobovsky's floor sensor), but there the fluid lies above or beside
// the point, so w = 1; the walls in the sum complete the kernel under a ceiling. One scan of
// the particles per call (those within reach of the face). `scratch` holds the indices of that
// scan, fluid first (reused between calls: no allocation once sized).
inline constexpr double kFaceWetKernelSum = 0.5;

template <int D, class K>
double face_pressure(const ParticleSet<D>& ps, const std::vector<double>& pressure, const K& kernel,
                     const std::vector<Vec<D>>& points, const Vec<D>& n, double offset, double rho0,
                     const Vec<D>& g, std::vector<std::uint32_t>& scratch) {
  if (pressure.size() < ps.size())
    throw std::invalid_argument("face_pressure: pressure array shorter than the particle set");
  const double s = kernel.support();
  Vec<D> lo = points.front(), hi = points.front();
  for (const auto& x : points) {
    lo = lo.cwiseMin(x + offset * n);
    hi = hi.cwiseMax(x + offset * n);
  }
  const auto near = [&](std::size_t j) {
    return !((ps.pos[j].array() < lo.array() - s) || (ps.pos[j].array() > hi.array() + s)).any();
  };
  // One scan: the fluid in `scratch`, the walls in a per-thread buffer appended after it (no
  // allocation once both have grown).
  static thread_local std::vector<std::uint32_t> walls;
  scratch.clear();
  walls.clear();
  for (std::size_t j = 0; j < ps.size(); ++j) {
    if (!near(j)) continue;
    (ps.role[j] == Role::Fluid ? scratch : walls).push_back(static_cast<std::uint32_t>(j));
  }
  const std::size_t n_fluid = scratch.size();
  scratch.insert(scratch.end(), walls.begin(), walls.end());
  const double correction = -rho0 * offset * g.dot(n);
  double sum = 0.0;
  for (const auto& x : points) {
    const Vec<D> q = x + offset * n;
    double sum_p = 0.0, sum_w = 0.0, sum_wall = 0.0, below = 0.0;
    for (std::size_t k = 0; k < scratch.size(); ++k) {
      const std::uint32_t j = scratch[k];
      const Vec<D> d = ps.pos[j] - q;
      const double r = d.norm();
      if (!(r < s)) continue;
      const double wv = kernel.w(r) * ps.mass[j] / ps.rho[j];
      if (k < n_fluid) {
        sum_p += pressure[j] * wv;
        sum_w += wv;
        below += wv * d.dot(g);
      } else {
        sum_wall += wv;
      }
    }
    if (!(sum_w > 0.0)) continue;
    const double wet = below > 0.0 ? std::min(1.0, (sum_w + sum_wall) / kFaceWetKernelSum) : 1.0;
    sum += (sum_p / sum_w + correction) * wet;
  }
  return sum / static_cast<double>(points.size());
}

// Velocity at point x: the same Shepard-normalised interpolation as probe_pressure applied
// to the fluid velocities (DualSPHysics' GaugeVelocity). Returns a vector of NaN when dry.
template <int D, class K>
Vec<D> probe_velocity(const ParticleSet<D>& ps, const K& kernel, const Vec<D>& x) {
  Vec<D> sum_v = Vec<D>::Zero();
  double sum_w = 0.0;
  gauge_detail::for_fluid_near(ps, x, kernel.support(), [&](std::size_t j, double r) {
    const double wv = kernel.w(r) * ps.mass[j] / ps.rho[j];
    sum_v += wv * ps.velocity(j);
    sum_w += wv;
  });
  if (!(sum_w > 0.0)) return Vec<D>::Constant(std::numeric_limits<double>::quiet_NaN());
  return sum_v / sum_w;
}

// Free-surface elevation on the vertical line through x_base (DualSPHysics' GaugeSwl):
// walk up from z0 = x_base[up] in steps dz to z_top, evaluating the (unnormalised) kernel
// sum of fluid mass rho_k(z) = sum_j m_j W(x(z) - x_j). It is about rho0 inside the fluid and
// about rho0/2 on the free surface, where the kernel is cut in half, so the surface is taken
// where rho_k first falls below `fraction * rho0` (fraction 0.5 by default; DualSPHysics uses
// 0.5 in 2D and 0.4 in 3D), linearly interpolated between the two bracketing samples.
//
// Walls are not summed, so rho_k also reads about rho0/2 at a bed: a start on (or just above)
// the floor is therefore allowed to be dry for up to one kernel support; the line is wet once
// a sample reaches the threshold. Returns z0 if no sample within one support above z0 is wet
// (a dry bed, or a layer thinner than about one support), and z_top if the fluid reaches it.
// Only particles whose horizontal distance to the line is below the support are summed.
// `sum_profile` (several ranks): each rank passes its own particles and a function that sums a
// vector over the ranks; the densities of every sample of the line are then summed before the
// walk (one reduction). Without it the walk evaluates the samples as it goes.
struct NoProfileSum {
  void operator()(std::vector<double>&) const {}
};
template <int D, class K, class ProfileSum = NoProfileSum>
double water_height(const ParticleSet<D>& ps, const K& kernel, const Vec<D>& x_base, int up,
                    double z_top, double dz, double rho0, double fraction = 0.5,
                    const ProfileSum* sum_profile = nullptr) {
  gauge_detail::check_line(x_base, up, z_top, dz);
  const double support = kernel.support();
  const double threshold = fraction * rho0;
  const double z0 = x_base[up];
  // Fluid particles within one support of the line, horizontally.
  const std::vector<std::uint32_t>& near = gauge_detail::line_candidates(
      ps, x_base, up, support, [&](std::size_t j) { return ps.role[j] == Role::Fluid; });
  auto sample_z = [&](long k) { return std::min(z0 + static_cast<double>(k) * dz, z_top); };
  auto density_at = [&](double z) {
    Vec<D> x = x_base;
    x[up] = z;
    return gauge_detail::mass_sum(ps, kernel, near, x);
  };
  thread_local std::vector<double> profile;
  if (sum_profile) {
    profile.clear();
    for (long k = 0;; ++k) {
      profile.push_back(density_at(sample_z(k)));
      if (sample_z(k) >= z_top) break;
    }
    (*sum_profile)(profile);
  }

  bool wet = false;
  double z_prev = z0, rho_prev = 0.0;
  for (long k = 0;; ++k) {
    const double z = sample_z(k);
    const double rho = sum_profile ? profile[static_cast<std::size_t>(k)] : density_at(z);
    if (rho >= threshold) {
      wet = true;
    } else if (wet) {
      // rho_prev >= threshold > rho: linear interpolation of the crossing.
      return z_prev + (z - z_prev) * (rho_prev - threshold) / (rho_prev - rho);
    } else if (z - z0 > support) {
      return z0;  // dry for a whole support above the start
    }
    if (z >= z_top) return wet ? z_top : z0;
    z_prev = z;
    rho_prev = rho;
  }
}

// Water level as the integral of the water fraction along the vertical line through x_base,
// from z0 = x_base[up] to z_top: z0 + int min(1, rho_k(z) / rho0) dz (trapezoid, step dz),
// rho_k the kernel sum of the mass of the fluid and of the wall particles below z0 (the bed,
// which completes the kernel at the bottom of the line; walls beside the line are not counted).
// interFoam's usual level, int alpha dz: a splash or a layer above a dry gap counts, unlike
// water_height's first free surface.
template <int D, class K>
double water_height_integral(const ParticleSet<D>& ps, const K& kernel, const Vec<D>& x_base,
                             int up, double z_top, double dz, double rho0) {
  gauge_detail::check_line(x_base, up, z_top, dz);
  const double z0 = x_base[up];
  const std::vector<std::uint32_t>& near = gauge_detail::line_candidates(
      ps, x_base, up, kernel.support(),
      [&](std::size_t j) { return ps.role[j] == Role::Fluid || ps.pos[j][up] < z0; });
  auto fraction_at = [&](double z) {
    Vec<D> x = x_base;
    x[up] = z;
    return std::min(1.0, gauge_detail::mass_sum(ps, kernel, near, x) / rho0);
  };
  const long n = std::max(1L, static_cast<long>(std::ceil((z_top - z0) / dz)));
  const double step = (z_top - z0) / static_cast<double>(n);
  double sum = 0.0, prev = fraction_at(z0);
  for (long k = 1; k <= n; ++k) {
    const double f = fraction_at(z0 + static_cast<double>(k) * step);
    sum += 0.5 * (prev + f) * step;
    prev = f;
  }
  return z0 + sum;
}

// Runup along a slope: the elevation (coordinate `up`) of the highest wet point of the line
// from `from` to `to`, two points on the slope surface (2D, or a line in a vertical plane in
// 3D), `from` below the lowest shoreline expected and `to` above the highest.
//
// Wet criterion: the line is sampled at steps ds at an offset of dp/2 along the slope's upward
// normal n (the centre of a first fluid layer on the surface), and a sample is wet where the
// kernel sum of fluid mass rho_k = sum_j m_j W(q - x_j) reaches `fraction * rho0`. Walls are
// not summed, so a layer two or more rows thick reads about 0.76 rho0 at that offset, a film of
// one particle row about 0.52 rho0 and a lone particle at most 0.28 rho0 (Wendland, h = 1.41 dp,
// particles on a dp lattice; the run's gauges call it with h = sqrt(D) dp whatever its coefh,
// run/gauge_set.cpp). The default fraction 0.3 thus counts a one-row film as wet and a
// lone particle as dry, and places the end of a layer cut normal to the slope within 0.2 dp of
// its edge (the last particle + dp/2; test_gauges measures it).
// The highest wet sample is found walking down from the top of the fluid along the line; the
// crossing to the dry sample above it is interpolated linearly. Returns from[up] if no sample
// is wet, to[up] if the top is. With `connected`, the edge of the tongue attached to the sea
// instead: the walk goes on down to `from`, and a wet stretch that a dry one longer than the
// kernel's support separates from the water below it (a splash thrown up the slope, a droplet
// left behind) does not count; a shorter dry stretch (a hole in a one-row film) does not cut
// the tongue. It costs the walk of the whole line, not only of its top.
//
// Candidates are the fluid particles within offset + support of the line, kept with their
// coordinate along it in a per-thread buffer (no allocation once grown: `sampling: max`
// gauges run this every step) and sorted by it, so each sample sums a window only.
template <int D, class K>
double runup_elevation(const ParticleSet<D>& ps, const K& kernel, const Vec<D>& from,
                       const Vec<D>& to, int up, double ds, double dp, double rho0,
                       double fraction = 0.3, bool connected = false) {
  if (up < 0 || up >= D) throw std::invalid_argument("runup_elevation: up axis out of range");
  if (!(ds > 0.0) || !(dp > 0.0))
    throw std::invalid_argument("runup_elevation: ds and dp must be positive");
  if (!(to[up] > from[up]))
    throw std::invalid_argument("runup_elevation: 'to' must lie above 'from'");
  const double length = (to - from).norm();
  const Vec<D> t = (to - from) / length;
  Vec<D> n = -t[up] * t;
  n[up] += 1.0;  // the vertical's part normal to the line
  if (!(n.norm() > 1e-9))
    throw std::invalid_argument("runup_elevation: the line must not be vertical");
  n.normalize();
  const double offset = 0.5 * dp;
  const double support = kernel.support();
  const double reach = offset + support;

  static thread_local std::vector<std::pair<double, std::uint32_t>> near;
  near.clear();
  double s_top = -std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < ps.size(); ++j) {
    if (ps.role[j] != Role::Fluid) continue;
    const Vec<D> r = ps.pos[j] - from;
    const double s = r.dot(t);
    if (s < -support || s > length + support) continue;
    if ((r - s * t).squaredNorm() >= reach * reach) continue;
    near.emplace_back(s, static_cast<std::uint32_t>(j));
    s_top = std::max(s_top, s);
  }
  const double z0 = from[up];
  if (near.empty()) return z0;
  std::sort(near.begin(), near.end());

  const double s2 = support * support;
  std::size_t lo = 0, hi = near.size();  // window [lo, hi) of candidates within the support
  auto density_at = [&](double s) {
    while (hi > 0 && near[hi - 1].first >= s + support) --hi;  // s only decreases
    while (lo > 0 && near[lo - 1].first > s - support) --lo;
    while (lo < hi && near[lo].first <= s - support) ++lo;
    const Vec<D> q = from + s * t + offset * n;
    double sum = 0.0;
    for (std::size_t k = lo; k < hi; ++k) {
      const std::uint32_t j = near[k].second;
      const double r2 = (q - ps.pos[j]).squaredNorm();
      if (r2 < s2) sum += ps.mass[j] * kernel.w(std::sqrt(r2));
    }
    return sum;
  };
  lo = near.size();
  const double threshold = fraction * rho0;
  // Walk down from the first sample above all candidates' reach (dry by construction).
  const double s_start = std::min(length, s_top + support);
  const long k_top = static_cast<long>(std::ceil(s_start / ds));
  double s_prev = std::min(length, static_cast<double>(k_top) * ds), rho_prev = density_at(s_prev);
  if (rho_prev >= threshold) return to[up];
  // The edge of the current wet stretch (NaN: none yet, or cut off by a long dry stretch), and
  // the length of the dry stretch walked since the last wet sample.
  double edge = std::numeric_limits<double>::quiet_NaN(), dry = 0.0;
  bool was_wet = false;
  for (long k = k_top - 1; k >= 0; --k) {
    const double s = static_cast<double>(k) * ds;
    const double rho = density_at(s);
    const bool wet = rho >= threshold;
    if (wet && !was_wet && std::isnan(edge)) {
      const double s_wet = s + (s_prev - s) * (rho - threshold) / (rho - rho_prev);
      if (!connected) return z0 + s_wet * t[up];
      edge = s_wet;
    }
    if (wet) {
      dry = 0.0;
    } else if (!std::isnan(edge)) {
      dry += s_prev - s;
      if (dry > support) edge = std::numeric_limits<double>::quiet_NaN();  // detached
    }
    was_wet = wet;
    s_prev = s;
    rho_prev = rho;
  }
  return std::isnan(edge) ? z0 : z0 + edge * t[up];
}

// Fluid load on a boundary body: force and moment in 3 components in both 2D and 3D (2D: only
// moment.z() is non-zero; force per unit width).
template <int D>
struct BodyLoad {
  Vec<D> force = Vec<D>::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  std::size_t particles = 0;  // active particles of the body that were summed
};

// Force and moment of the fluid on boundary body `body` (its id in ps.body, the index of the
// body in the case file): F = sum_a m_a ace_a, M = sum_a (x_a - about) x m_a ace_a over the
// active boundary particles a of that body, where `acceleration` holds, for wall particles,
// the force per unit mass exerted on them by the fluid (Simulation::acceleration(), indexed
// as ps). Pair forces are antisymmetric, so this is exactly minus the force the body exerts on
// the fluid in the SPH momentum balance (as DualSPHysics' ComputeForces / GaugeForce).
template <int D>
BodyLoad<D> body_load(const ParticleSet<D>& ps, const std::vector<Vec<D>>& acceleration,
                      std::uint16_t body, const Eigen::Vector3d& about) {
  if (acceleration.size() < ps.size())
    throw std::invalid_argument("body_load: acceleration array shorter than the particle set");
  BodyLoad<D> load;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.body[a] != body || !is_wall(ps.role[a])) continue;
    const Vec<D> f = ps.mass[a] * acceleration[a];
    Eigen::Vector3d f3 = Eigen::Vector3d::Zero(), r3 = Eigen::Vector3d::Zero();
    f3.template head<D>() = f;
    r3.template head<D>() = ps.pos[a];
    load.force += f;
    load.moment += (r3 - about).cross(f3);
    ++load.particles;
  }
  if constexpr (D == 2) load.moment.template head<2>().setZero();  // about may have z != 0
  return load;
}

}  // namespace swell
