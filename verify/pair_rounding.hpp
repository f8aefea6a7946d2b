// A bound on the rounding of the WCSPH pair loop's float arithmetic (PairReal, types.hpp), for
// the checks that compare its results with exact or double-precision ones (tests and
// `swell verify angular_momentum`).
//
// Each particle's rate is a sum over its n neighbours of terms computed with ~20 roundings each
// (r_ab rounded from the double difference, r^2, sqrt, the kernel, P/rho^2 and Pi_ab, the
// products); with u the unit roundoff of PairReal, the standard forward bound of a sum of
// computed terms (Higham 2002, "Accuracy and stability of numerical algorithms", eq. 4.4 and
// lemma 3.1) is gamma_(n + K) times the sum of the terms' magnitudes, K = 32 covering the
// per-term roundings and the kernel's conditioning (|r dF/dr| <= 3 max|F| for every kernel
// here; the quintic's three terms cancel, which adds up to 8u/q of |F(0)| per term: K = 128 for
// it, covering q >= 0.1). The magnitudes are majorised with the kernel factor at its largest,
// |F(0)|, because
// near the support's edge F's relative error is large while its size is not. In a double
// build u = 1.1e-16 and the bound is negligible.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "solver/physics/eos.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

struct PairRounding {
  std::vector<double> acc;   // per particle: bound on |error| of each component of dv/dt
  std::vector<double> drho;  // per particle: bound on |error| of drho/dt
  double visc = 0.0;         // bound on the error of the viscous time-step signal
  // Bound on |error of sum_a m_a dv_a/dt| (each component).
  template <int D>
  double momentum(const ParticleSet<D>& ps) const {
    double s = 0.0;
    for (std::size_t a = 0; a < ps.size(); ++a) s += ps.mass[a] * acc[a];
    return s;
  }
};

// Brute force over every pair, periodic axes by the minimum image (so it holds between steps,
// when no images are stored): for the small sets of tests and verification cases only. Walls
// see fluid only (DBC's selection).
template <int D>
PairRounding pair_rounding(const ParticleSet<D>& ps, const SolverParams& p) {
  constexpr double u = 0.5 * std::numeric_limits<PairReal>::epsilon();
  const double K = p.kernel == KernelType::Quintic ? 128.0 : 32.0;
  const TaitEos eos(p.rho0, p.c0, p.gamma);
  const double support = kernel_support_factor(p.kernel) * p.h;
  const double s2 = support * support, eta2 = p.eta2();
  const double fmax =
      with_kernel<D>(p.kernel, p.h, [](const auto& k) { return std::abs(k.f(1e-9 * k.h)); });
  const double g = p.gravity.norm();
  const double coef = p.diffusion != DiffusionModel::None ? p.delta * p.h * p.c0 : 0.0;
  const double rho0_c2 = p.diffusion == DiffusionModel::Fourtakas ? p.rho0 / (p.c0 * p.c0) : 0.0;
  const std::size_t n = ps.size();
  const Vec<D> period = (p.domain_max - p.domain_min).template head<D>();
  PairRounding out;
  out.acc.assign(n, 0.0);
  out.drho.assign(n, 0.0);
  std::vector<double> prs(n), cs(n);  // |P| / rho^2 and c per particle
  for (std::size_t i = 0; i < n; ++i) {
    const double rho = ps.rho[i];
    prs[i] = std::abs(eos.pressure(rho)) / (rho * rho);
    cs[i] = eos.sound_speed(rho);
  }
  double visc = 0.0;
  for (std::size_t a = 0; a < n; ++a) {
    const bool fa = ps.role[a] == Role::Fluid;
    const double rho_a = ps.rho[a], prs_a = prs[a], cs_a = cs[a];
    double A = 0.0, Dr = 0.0, count = 0.0;
    for (std::size_t b = 0; b < n; ++b) {
      const bool fb = ps.role[b] == Role::Fluid;
      if (b == a || (!fa && !fb)) continue;
      Vec<D> rab = ps.pos[a] - ps.pos[b];
      for (int d = 0; d < D; ++d)
        if (p.periodic[d]) rab[d] -= period[d] * std::round(rab[d] / period[d]);
      const double r2 = rab.squaredNorm();
      if (r2 >= s2) continue;
      const double r = std::sqrt(r2), w = (ps.velocity(a) - ps.velocity(b)).norm();
      const double rho_b = ps.rho[b], m_b = ps.mass[b];
      const double inv_r2e = 1.0 / (r2 + eta2);
      double pterm = prs_a + prs[b];
      if (p.viscosity == ViscosityModel::Artificial)
        pterm += p.alpha * 0.5 * (cs_a + cs[b]) * p.h * w * r * inv_r2e / (0.5 * (rho_a + rho_b));
      A += m_b * pterm * fmax * r;
      if (p.viscosity == ViscosityModel::Laminar)
        A += m_b * 4.0 * p.nu * r2 * fmax / (rho_a + rho_b) * inv_r2e * w;
      Dr += m_b * fmax * w * r;
      if (fa && fb)
        Dr += 2.0 * coef * (std::abs(rho_b - rho_a) + rho0_c2 * g * r) * r2 * fmax * inv_r2e * m_b /
              rho_b;
      visc = std::max(visc, p.h * w * r * inv_r2e);
      count += 1.0;
    }
    const double gamma = (count + K) * u / (1.0 - (count + K) * u);
    out.acc[a] = gamma * A;
    out.drho[a] = gamma * Dr;
  }
  out.visc = 16.0 * u * visc;  // h v_ab.r_ab / (r^2 + eta^2): a 3-term dot product and 4 roundings
  return out;
}

}  // namespace swell
