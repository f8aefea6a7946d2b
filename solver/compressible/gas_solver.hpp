// Compressible SPH for an ideal gas (Price 2012, J. Comput. Phys. 231:759; Springel &
// Hernquist 2002): variable smoothing length solved with the summation density, grad-h terms,
// Monaghan (1997) signal-velocity artificial viscosity with its heating, and a kick-drift-kick
// leapfrog. Separate from the WCSPH solver: its own particle arrays, neighbour bins and step.
//
//   h_a = eta (m_a/rho_a)^(1/D),  rho_a = sum_b m_b W(r_ab, h_a)    (Newton on h, bisection
//   Omega_a = 1 + h_a/(D rho_a) sum_b m_b dW_ab(h_a)/dh_a             fallback)
//   dv_a/dt = -sum_b m_b [P_a/(Omega_a rho_a^2) gradW(h_a) + P_b/(Omega_b rho_b^2) gradW(h_b)
//                         + Pi_ab (gradW(h_a) + gradW(h_b))/2]
//   du_a/dt = P_a/(Omega_a rho_a^2) sum_b m_b v_ab.gradW(h_a) + 1/2 sum_b m_b Pi_ab v_ab.gradW_mean
//   Pi_ab = -alpha v_sig w_ab / (2 rho_mean), v_sig = c_a + c_b - beta w_ab, for w_ab < 0
// These forms conserve sum m (v^2/2 + u) exactly in the spatial discretisation.
//
// Walls are mirror planes (free slip): every particle within reach of a wall plane has a ghost
// reflected through it (velocity normal component flipped) that copies its state after the
// density solve. The kernel is the cubic spline with eta = 1.2 (Price 2012, section 4: about
// 2 eta neighbours per unit length per dimension), support 2h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <vector>

#include "solver/compressible/ideal_gas.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/state/types.hpp"

namespace swell::compressible {

struct GasParams {
  double gamma = 1.4;
  double eta = 1.2;            // h = eta (m/rho)^(1/D)
  double alpha = 1.0;          // Monaghan (1997) viscosity
  double beta = 2.0;           // v_sig = c_a + c_b - beta w_ab
  double courant = 0.3;        // dt = courant h / v_sig
  double force_factor = 0.25;  // dt = force_factor sqrt(h / |a|)
  double h_tolerance = 1e-10;  // relative change of h that ends the Newton iterations
};

// K: the kernel (CubicSpline by default; WendlandC2 where many neighbours are needed, since
// the Wendland functions do not pair at any neighbour number: Dehnen & Aly 2012, MNRAS 425:1068).
template <int D, class K = CubicSpline<D>>
class GasSolver {
 public:
  using V = Vec<D>;
  using Kernel = K;

  // Particles: positions, velocities, masses, specific internal energies. lo/hi bound the box;
  // mirror[d] puts mirror walls at lo[d] and hi[d] (otherwise the direction is open).
  GasSolver(GasParams p, V lo, V hi, std::array<bool, D> mirror)
      : p_(p), lo_(lo), hi_(hi), mirror_(mirror), eos_{p.gamma} {}

  void add(const V& x, const V& v, double m, double u, double h_guess) {
    pos.push_back(x);
    vel.push_back(v);
    mass.push_back(m);
    this->u.push_back(u);
    h.push_back(h_guess);
    ++n_;
  }
  std::size_t size() const { return n_; }

  // Densities, forces and the first dt at t = 0.
  void initialise() {
    acc.assign(n_, V::Zero());
    du.assign(n_, 0.0);
    v_half.assign(n_, V::Zero());
    u_half.assign(n_, 0.0);
    evaluate();
  }

  // One kick-drift-kick step: half kick, drift, density at the new positions, forces with
  // the predicted v and u, closing half kick. Second order in dt.
  void step(double dt) {
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t a = 0; a < std::ptrdiff_t(n_); ++a) {
      v_half[a] = vel[a] + 0.5 * dt * acc[a];
      u_half[a] = u[a] + 0.5 * dt * du[a];
      pos[a] += dt * v_half[a];
      vel[a] = v_half[a] + 0.5 * dt * acc[a];  // predicted for the force evaluation
      u[a] = u_half[a] + 0.5 * dt * du[a];
    }
    evaluate();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t a = 0; a < std::ptrdiff_t(n_); ++a) {
      vel[a] = v_half[a] + 0.5 * dt * acc[a];
      u[a] = u_half[a] + 0.5 * dt * du[a];
    }
    time_ += dt;
  }

  double time() const {
    return time_;
  }
  // The CFL step of the last evaluation: min over particles of courant h/v_sig and
  // force_factor sqrt(h/|a|).
  double dt_cfl() const {
    return dt_;
  }

  double total_energy() const {
    double e = 0.0;
    for (std::size_t a = 0; a < n_; ++a) e += mass[a] * (0.5 * vel[a].squaredNorm() + u[a]);
    return e;
  }
  V total_momentum() const {
    V s = V::Zero();
    for (std::size_t a = 0; a < n_; ++a) s += mass[a] * vel[a];
    return s;
  }
  // sum m (v.a + du/dt): zero up to round-off for the conservative forms (walls aside).
  double energy_rate() const {
    double e = 0.0;
    for (std::size_t a = 0; a < n_; ++a) e += mass[a] * (vel[a].dot(acc[a]) + du[a]);
    return e;
  }

  const IdealGas& eos() const {
    return eos_;
  }

  // Per particle (real ones in [0, size()), ghosts after them).
  std::vector<V> pos, vel, acc, v_half;
  std::vector<double> mass, u, du, u_half, h, rho, omega, pressure, sound;

 private:
  void evaluate() {
    double h_max = 0.0;
    for (std::size_t a = 0; a < n_; ++a) h_max = std::max(h_max, h[a]);
    h_cap_ = std::max(h_cap_, 1.25 * h_max);
    for (int attempt = 0;; ++attempt) {
      make_ghosts();
      bin();
      if (solve_density()) break;
      if (attempt > 20) throw std::runtime_error("gas solver: smoothing length keeps growing");
      h_cap_ *= 1.5;  // some particle wanted more than the reach: widen and redo
    }
    copy_to_ghosts();
    forces();
  }

  // Ghost particles: reflections of every particle within reach of a wall plane, through
  // each wall combination (faces, edges, corners).
  void make_ghosts() {
    const double reach = Kernel::kSupport * h_cap_;
    std::size_t total = n_;
    ghost_src_.clear();
    ghost_flip_.clear();
    for (std::size_t a = 0; a < n_; ++a) {
      // side[d]: 0 none, 1 lo wall, 2 hi wall, for the walls this particle is near.
      std::array<int, D> near{};
      for (int d = 0; d < D; ++d) {
        near[d] = 0;
        if (!mirror_[d]) continue;
        if (pos[a][d] - lo_[d] < reach)
          near[d] = 1;
        else if (hi_[d] - pos[a][d] < reach)
          near[d] = 2;
      }
      int combos = 1;
      for (int d = 0; d < D; ++d) combos *= 2;
      for (int c = 1; c < combos; ++c) {  // every non-empty subset of the near walls
        bool ok = true;
        for (int d = 0; d < D; ++d)
          if ((c >> d & 1) && near[d] == 0) ok = false;
        if (!ok) continue;
        ghost_src_.push_back(a);
        ghost_flip_.push_back(c);
      }
    }
    total += ghost_src_.size();
    resize(total);
    for (std::size_t g = 0; g < ghost_src_.size(); ++g) {
      const std::size_t a = ghost_src_[g], i = n_ + g;
      V x = pos[a];
      for (int d = 0; d < D; ++d)
        if (ghost_flip_[g] >> d & 1) {
          const double wall = pos[a][d] - lo_[d] < hi_[d] - pos[a][d] ? lo_[d] : hi_[d];
          x[d] = 2.0 * wall - x[d];
        }
      pos[i] = x;
      mass[i] = mass[a];
    }
  }

  void resize(std::size_t total) {
    pos.resize(total);
    vel.resize(total);
    mass.resize(total);
    u.resize(total);
    h.resize(total);
    rho.resize(total);
    omega.resize(total);
    pressure.resize(total);
    sound.resize(total);
  }

  // Uniform cells of the reach (the largest support), counting sort of all particles.
  void bin() {
    const std::size_t total = pos.size();
    cell_ = Kernel::kSupport * h_cap_;
    V mn = pos[0], mx = pos[0];
    for (std::size_t i = 1; i < total; ++i) {
      mn = mn.cwiseMin(pos[i]);
      mx = mx.cwiseMax(pos[i]);
    }
    origin_ = mn;
    std::size_t ncell = 1;
    for (int d = 0; d < D; ++d) {
      dims_[d] = int((mx[d] - mn[d]) / cell_) + 1;
      ncell *= std::size_t(dims_[d]);
    }
    start_.assign(ncell + 1, 0);
    cell_of_.resize(total);
    order_.resize(total);
    for (std::size_t i = 0; i < total; ++i) {
      cell_of_[i] = cell_index(pos[i]);
      ++start_[cell_of_[i] + 1];
    }
    for (std::size_t c = 0; c < ncell; ++c) start_[c + 1] += start_[c];
    fill_ = start_;
    for (std::size_t i = 0; i < total; ++i) order_[fill_[cell_of_[i]]++] = i;
  }
  std::size_t cell_index(const V& x) const {
    std::size_t c = 0;
    for (int d = D - 1; d >= 0; --d) {
      const int k = std::clamp(int((x[d] - origin_[d]) / cell_), 0, dims_[d] - 1);
      c = c * std::size_t(dims_[d]) + std::size_t(k);
    }
    return c;
  }
  // fn(b) for every particle b in the 3^D cells around x (b may be the particle itself).
  template <class Fn>
  void for_each_candidate(const V& x, Fn&& fn) const {
    std::array<int, D> k;
    for (int d = 0; d < D; ++d)
      k[d] = std::clamp(int((x[d] - origin_[d]) / cell_), 0, dims_[d] - 1);
    int nb = 1;
    for (int d = 0; d < D; ++d) nb *= 3;
    for (int o = 0; o < nb; ++o) {
      std::size_t c = 0;
      bool inside = true;
      int rest = o;
      std::array<int, D> kk;
      for (int d = 0; d < D; ++d) {
        kk[d] = k[d] + rest % 3 - 1;
        rest /= 3;
        if (kk[d] < 0 || kk[d] >= dims_[d]) inside = false;
      }
      if (!inside) continue;
      for (int d = D - 1; d >= 0; --d) c = c * std::size_t(dims_[d]) + std::size_t(kk[d]);
      for (std::size_t j = start_[c]; j < start_[c + 1]; ++j) fn(order_[j]);
    }
  }

  // Summation density and h together, per particle: Newton on
  // F(h) = sum_b m_b W(r_ab, h) - m_a (eta/h)^D, safeguarded by a bracket (bisection when a
  // Newton step leaves it). Returns false when a particle needs h above the reach.
  bool solve_density() {
    int failed = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : failed)
    for (std::ptrdiff_t ia = 0; ia < std::ptrdiff_t(n_); ++ia) {
      const std::size_t a = std::size_t(ia);
      auto eval = [&](double hh, double& sum, double& dsum) {
        const Kernel k(hh);
        const double r2max = k.support() * k.support();
        sum = 0.0;
        dsum = 0.0;
        for_each_candidate(pos[a], [&](std::size_t b) {
          const double r2 = (pos[a] - pos[b]).squaredNorm();
          if (r2 >= r2max) return;
          const double r = std::sqrt(r2);
          sum += mass[b] * k.w(r);
          dsum += mass[b] * k.dwdh(r);
        });
      };
      const double m = mass[a], etaD = std::pow(p_.eta, D);
      double hh = std::min(h[a], h_cap_), lo = 0.0, hi = h_cap_;
      double sum = 0.0, dsum = 0.0;
      bool done = false;
      for (int it = 0; it < 100; ++it) {
        eval(hh, sum, dsum);
        const double rho_h = m * etaD / std::pow(hh, D);
        const double F = sum - rho_h, dF = dsum + D * rho_h / hh;
        // F < 0 at small h (self term only), > 0 at large h: keep the sign-change bracket.
        if (F < 0.0)
          lo = hh;
        else
          hi = hh;
        double next = hh - F / dF;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // bisection fallback
        if (std::abs(next - hh) < p_.h_tolerance * hh) {
          hh = next;
          done = true;
          break;
        }
        hh = next;
      }
      if (!done || hh > 0.999 * h_cap_) {
        ++failed;
        continue;
      }
      eval(hh, sum, dsum);
      h[a] = hh;
      rho[a] = sum;
      omega[a] = 1.0 + hh / (D * sum) * dsum;  // 1 - (dh/drho) sum m dW/dh, dh/drho = -h/(D rho)
      pressure[a] = eos_.pressure(sum, u[a]);
      sound[a] = eos_.sound_speed(sum, u[a]);
    }
    return failed == 0;
  }

  void copy_to_ghosts() {
    for (std::size_t g = 0; g < ghost_src_.size(); ++g) {
      const std::size_t a = ghost_src_[g], i = n_ + g;
      V v = vel[a];
      for (int d = 0; d < D; ++d)
        if (ghost_flip_[g] >> d & 1) v[d] = -v[d];
      vel[i] = v;
      u[i] = u[a];
      h[i] = h[a];
      rho[i] = rho[a];
      omega[i] = omega[a];
      pressure[i] = pressure[a];
      sound[i] = sound[a];
    }
  }

  void forces() {
    double dt = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(dynamic, 64) reduction(min : dt)
    for (std::ptrdiff_t ia = 0; ia < std::ptrdiff_t(n_); ++ia) {
      const std::size_t a = std::size_t(ia);
      const Kernel ka(h[a]);
      const double qa = pressure[a] / (omega[a] * rho[a] * rho[a]);
      V f = V::Zero();
      double e = 0.0, vsig_max = sound[a];
      for_each_candidate(pos[a], [&](std::size_t b) {
        const V rab = pos[a] - pos[b];
        const double r2 = rab.squaredNorm();
        const double sup = Kernel::kSupport * std::max(h[a], h[b]);
        if (r2 >= sup * sup || r2 == 0.0) return;
        const double r = std::sqrt(r2);
        const Kernel kb(h[b]);
        const double fa = ka.f(r), fb = kb.f(r);  // gradW = r_ab f
        const double qb = pressure[b] / (omega[b] * rho[b] * rho[b]);
        const V vab = vel[a] - vel[b];
        const double vr = vab.dot(rab), w = vr / r;
        const double vsig = sound[a] + sound[b] - p_.beta * std::min(w, 0.0);
        vsig_max = std::max(vsig_max, vsig);
        const double pi = w < 0.0 ? -p_.alpha * vsig * w / (rho[a] + rho[b]) : 0.0;
        const double fmean = 0.5 * (fa + fb);
        f -= mass[b] * (qa * fa + qb * fb + pi * fmean) * rab;
        e += mass[b] * (qa * fa + 0.5 * pi * fmean) * vr;
      });
      acc[a] = f;
      du[a] = e;
      const double an = f.norm();
      double dta = p_.courant * h[a] / vsig_max;
      if (an > 0.0) dta = std::min(dta, p_.force_factor * std::sqrt(h[a] / an));
      dt = std::min(dt, dta);
    }
    dt_ = dt;
  }

  GasParams p_;
  V lo_, hi_;
  std::array<bool, D> mirror_;
  IdealGas eos_;
  std::size_t n_ = 0;
  double time_ = 0.0, dt_ = 0.0, h_cap_ = 0.0, cell_ = 1.0;
  std::vector<std::size_t> ghost_src_;
  std::vector<int> ghost_flip_;
  V origin_;
  std::array<int, D> dims_{};
  std::vector<std::size_t> start_, fill_, cell_of_, order_;
};

}  // namespace swell::compressible
