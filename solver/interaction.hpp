// The particle-pair loop, written once (STYLE.md): for every active particle a, gather the
// contributions of its neighbours b into drho_a/dt and dv_a/dt. Parallel over cells with
// OpenMP; each thread writes only the particles of its own cells, so there are no atomics.
//
// Equations (DESIGN.md, defaults as DualSPHysics):
//   drho_a/dt = sum_b m_b v_ab . gradW_ab + density diffusion (fluid-fluid pairs)
//   dv_a/dt   = -sum_b m_b (P_a/rho_a^2 + P_b/rho_b^2 + Pi_ab) gradW_ab + viscous + g
// Boundary (DBC) particles get drho/dt from their fluid neighbours only; their `ace` holds the
// force per unit mass exerted on them by the fluid (for force gauges) and is never integrated.
#pragma once

#include <immintrin.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "solver/cell_grid.hpp"
#include "solver/particle_set.hpp"
#include "solver/physics_terms.hpp"
#include "solver/solver_params.hpp"

namespace swell {

template <int D>
struct ForceBuffers {
  std::vector<Vec<D>> ace;
  std::vector<double> drho;
  std::vector<double> prs;    // P_a / rho_a^2
  std::vector<double> press;  // P_a, filled only on request (Simulation::pressure(), output)
  double visc_dt_max = 0.0;   // max over pairs of h |v_ab.r_ab| / (r^2 + eta^2), for dt
  double cs_max = 0.0;
  // One neighbour list per thread, reused across particles and steps (grows, never shrinks).
  std::vector<std::vector<std::uint32_t>> neighbours;

  void resize(std::size_t n) {
    ace.resize(n);
    drho.resize(n);
    prs.resize(n);
  }
};

// P/rho^2 of every active particle and the largest sound speed (for dt).
template <int D>
void compute_pressure(const ParticleSet<D>& ps, const TaitEos& eos, ForceBuffers<D>& out) {
  const long n = static_cast<long>(ps.size());
  double rho_max = 0.0;
#pragma omp parallel for schedule(static) reduction(max : rho_max)
  for (long i = 0; i < n; ++i) {
    const double rho = ps.rho[i];
    out.prs[i] = eos.pressure(rho) / (rho * rho);
    rho_max = std::max(rho_max, rho);
  }
  out.cs_max = eos.sound_speed(rho_max);  // c grows with rho
}

// Lanes of the pair loop's vectors (8 doubles with AVX-512); neighbour lists are padded to it.
inline constexpr std::uint32_t kPairLanes = 8;
// Neighbour-list entries carry the wall flag in their top bit (b | kWallBit for a wall b).
inline constexpr std::uint32_t kWallBit = 0x80000000u;

// Appends to nb[k...] the entries of the particles b in [b0, b1) within the kernel support of
// xa (b != a; for a wall particle a only fluid b, since wall-wall pairs do nothing under DBC)
// and returns the new count. P holds the positions (D doubles a particle), kind the kinds. nb
// must have room for (b1 - b0) + 8 more entries past k. The AVX-512 path tests 8 candidates at
// once and packs the hits with a register compress; the scalar path is the same test.
template <int D>
inline std::uint32_t gather_neighbours(const double* P, const Kind* kind, const double* xa,
                                       bool fluid_a, double support2, std::uint32_t b0,
                                       std::uint32_t b1, std::uint32_t* nb, std::uint32_t k) {
  std::uint32_t b = b0;
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
  static_assert(D == 2 || D == 3, "the AVX-512 path handles 2D and 3D");
  const __m512d s2 = _mm512_set1_pd(support2), tiny = _mm512_set1_pd(1e-18),
                zero = _mm512_setzero_pd();
  __m512d xav[D];
  for (int d = 0; d < D; ++d) xav[d] = _mm512_set1_pd(xa[d]);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i wall_bit = _mm256_set1_epi32(static_cast<int>(kWallBit));
  const __m128i fluid_kind = _mm_set1_epi8(static_cast<char>(Kind::Fluid));
  for (; b < b1; b += 8) {
    const std::uint32_t left = b1 - b;
    const __mmask8 valid = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
    // The 8 candidates' coordinates are D x 8 consecutive doubles: load them (masked at the
    // end of the range) and split them by axis with two-source permutes.
    const double* p = P + static_cast<std::size_t>(b) * D;
    const unsigned nd = (left >= 8 ? 8u : left) * D;  // doubles to read
    auto part = [nd](unsigned from) {
      return nd >= from + 8 ? __mmask8(0xFF)
                            : nd > from ? __mmask8((1u << (nd - from)) - 1u) : __mmask8(0);
    };
    __m512d xb[D];
    const __m512d c0 = _mm512_maskz_loadu_pd(part(0), p), c1 = _mm512_maskz_loadu_pd(part(8), p + 8);
    if constexpr (D == 2) {
      xb[0] = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), c1);
      xb[1] = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15), c1);
    } else {
      const __m512d c2 = _mm512_maskz_loadu_pd(part(16), p + 16);
      const __m512d tx = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(0, 3, 6, 9, 12, 15, 0, 0), c1);
      const __m512d ty = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(1, 4, 7, 10, 13, 0, 0, 0), c1);
      const __m512d tz = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(2, 5, 8, 11, 14, 0, 0, 0), c1);
      xb[0] = _mm512_permutex2var_pd(tx, _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 10, 13), c2);
      xb[1] = _mm512_permutex2var_pd(ty, _mm512_setr_epi64(0, 1, 2, 3, 4, 8, 11, 14), c2);
      xb[2] = _mm512_permutex2var_pd(tz, _mm512_setr_epi64(0, 1, 2, 3, 4, 9, 12, 15), c2);
    }
    __m512d r2 = zero;
    for (int d = 0; d < D; ++d) {
      const __m512d dx = _mm512_sub_pd(xav[d], xb[d]);
      r2 = _mm512_fmadd_pd(dx, dx, r2);
    }
    const __m128i kb = _mm_maskz_loadu_epi8(valid, kind + b);
    const __mmask8 fluid_b = static_cast<__mmask8>(_mm_cmpeq_epi8_mask(kb, fluid_kind));
    __mmask8 m = valid & _mm512_cmp_pd_mask(r2, s2, _CMP_LT_OQ) &
                 _mm512_cmp_pd_mask(r2, tiny, _CMP_GT_OQ);
    if (!fluid_a) m &= fluid_b;
    __m256i idx = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(b)), lane);
    idx = _mm256_mask_or_epi32(idx, static_cast<__mmask8>(~fluid_b), idx, wall_bit);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(nb + k), _mm256_maskz_compress_epi32(m, idx));
    k += static_cast<std::uint32_t>(__builtin_popcount(m));
  }
#else
  for (; b < b1; ++b) {
    double r2 = 0.0;
    for (int d = 0; d < D; ++d) {
      const double dx = xa[d] - P[b * D + d];
      r2 += dx * dx;
    }
    const bool fluid_b = kind[b] == Kind::Fluid;
    nb[k] = b | (fluid_b ? 0u : kWallBit);
    k += (r2 < support2) & (r2 > 1e-18) & (fluid_a | fluid_b);
  }
#endif
  return k;
}

// For every active particle a, in two passes:
//  1. scan the 3^(D-1) contiguous candidate ranges of its cell and keep the particles b within
//     the kernel support (gather_neighbours);
//  2. evaluate the pair terms over that short list in one SIMD loop (gathers, masks instead of
//     branches, sums and maxima as reductions).
// Each particle's sums run over its neighbours in a fixed order, so results do not depend on
// the thread count. Positions and velocities are read in place (D doubles a particle), and the
// sound speed c_b = c0 (rho_b/rho0)^3 is computed from rho_b (Tait, gamma = 7), so the loop
// keeps no copies of the particle state.
template <int D, class Kernel, ViscosityModel VM>
void interact(const ParticleSet<D>& ps, const CellGrid<D>& grid, const Kernel& kernel,
              const SolverParams& prm, ForceBuffers<D>& out) {
  using V = Vec<D>;
  static_assert(sizeof(V) == D * sizeof(double), "positions must be D packed doubles");
  if (prm.gamma != 7.0) throw std::invalid_argument("interact: the pair loop assumes gamma = 7");
  const double support2 = kernel.support() * kernel.support();
  const double h = prm.h, eta2 = prm.eta2();
  const V g = prm.gravity.template head<D>();
  const double alpha = prm.alpha, nu4 = 4.0 * prm.nu;
  const double c0 = prm.c0, inv_rho0 = 1.0 / prm.rho0;
  const bool diffuse = prm.diffusion != DiffusionModel::None;
  // Density diffusion (physics_terms.hpp, DensityDiffusion): coef = delta h c0, and the
  // hydrostatic part rho0 g.(x_b - x_a) / c0^2 for Fourtakas et al. (2019).
  const double dd_coef = diffuse ? prm.delta * h * prm.c0 : 0.0;
  const double dd_hydro =
      prm.diffusion == DiffusionModel::Fourtakas ? prm.rho0 / (prm.c0 * prm.c0) : 0.0;
  const long ncells = static_cast<long>(grid.num_cells());
  const int nthreads = omp_get_max_threads();
  if (static_cast<int>(out.neighbours.size()) < nthreads) out.neighbours.resize(nthreads);
  double visc_dt_max = 0.0;

  const double* P = ps.pos.data()->data();
  const double* U = ps.vel.data()->data();
  const Kind* kind = ps.kind.data();
  const double* rho = ps.rho.data();
  const double* mass = ps.mass.data();
  const double* prs = out.prs.data();

#pragma omp parallel reduction(max : visc_dt_max)
  {
    std::vector<std::uint32_t>& nbv = out.neighbours[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 16)
    for (long c = 0; c < ncells; ++c) {
      const std::uint32_t cb = grid.begin(c), ce = grid.end(c);
      if (cb == ce) continue;
      if (!grid.fluid_near(c)) {  // dry wall cell: nothing to gather
        for (std::uint32_t a = cb; a < ce; ++a) {
          out.drho[a] = 0.0;
          out.ace[a] = V::Zero();
        }
        continue;
      }
      std::array<std::pair<std::uint32_t, std::uint32_t>, (D == 3 ? 9 : 3)> ranges;
      int nr = 0;
      std::size_t candidates = 0;
      grid.for_each_neighbour_range(c, [&](std::uint32_t b, std::uint32_t e) {
        ranges[nr++] = {b, e};
        candidates += e - b;
      });
      if (nbv.size() < candidates + 2 * kPairLanes)
        nbv.resize(candidates + candidates / 2 + 2 * kPairLanes);  // rare, amortised
      std::uint32_t* nb = nbv.data();

      for (std::uint32_t a = cb; a < ce; ++a) {
        double xa[3] = {0.0, 0.0, 0.0}, va[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < D; ++d) {
          xa[d] = P[a * D + d];
          va[d] = U[a * D + d];
        }
        const bool fluid_a = kind[a] == Kind::Fluid;
        // Pass 1: neighbour list. A wall particle keeps fluid neighbours only.
        std::uint32_t k = 0;
        for (int r = 0; r < nr; ++r)
          k = gather_neighbours<D>(P, kind, xa, fluid_a, support2, ranges[r].first,
                                   ranges[r].second, nb, k);
        // Pad to a whole number of SIMD lanes with the particle itself: pass 2 gives a
        // coincident pair exactly zero, so the vector loop needs no scalar remainder.
        while (k % kPairLanes) nb[k++] = a;

        // Pass 2: pair terms.
        const double rho_a = rho[a], prs_a = prs[a];
        const double ra = rho_a * inv_rho0, cs_a = c0 * ra * ra * ra;
        const double dd_a = fluid_a ? -2.0 * dd_coef : 0.0;  // walls: continuity only (DBC)
        // In 2D the third axis is not used and compiles away.
        const double g0 = g[0], g1 = g[1], g2 = g[D - 1];
        const double xa0 = xa[0], xa1 = xa[1], xa2 = xa[2];
        const double va0 = va[0], va1 = va[1], va2 = va[2];
        double drho = 0.0, vdt = 0.0, ac0 = 0.0, ac1 = 0.0, ac2 = 0.0;
#pragma omp simd reduction(+ : drho, ac0, ac1, ac2) reduction(max : vdt)
        for (std::uint32_t j = 0; j < k; ++j) {
          const std::uint32_t e = nb[j];
          const std::uint32_t b = e & ~kWallBit;
          const double fluid_b = (e & kWallBit) ? 0.0 : 1.0;
          const double r0 = xa0 - P[b * D], r1 = xa1 - P[b * D + 1];
          const double r2c = D == 3 ? xa2 - P[b * D + D - 1] : 0.0;
          const double w0 = va0 - U[b * D], w1 = va1 - U[b * D + 1];
          const double w2 = D == 3 ? va2 - U[b * D + D - 1] : 0.0;
          const double r2 = r0 * r0 + r1 * r1 + r2c * r2c;
          const double vr = w0 * r0 + w1 * r1 + w2 * r2c;  // v_ab . r_ab
          const double grx = g0 * r0 + g1 * r1 + (D == 3 ? g2 * r2c : 0.0);
          // gradW_ab = r_ab fr. Real pairs have r2 > 1e-18 (pass 1); the padding entries
          // (r_ab = v_ab = 0) get a finite fr, so every term below is exactly zero for them.
          const double fr = kernel.fs(std::sqrt(std::max(r2, 1e-18)));
          const double m_b = mass[b], rho_b = rho[b];
          const double inv_r2e = 1.0 / (r2 + eta2);
          drho += m_b * fr * vr;  // m_b v_ab . gradW_ab
          // Approaching pairs: the viscous time-step limit and Monaghan's Pi_ab.
          const double mu = vr < 0.0 ? h * vr * inv_r2e : 0.0;
          vdt = vdt > -mu ? vdt : -mu;
          double pterm = prs_a + prs[b];
          if constexpr (VM == ViscosityModel::Artificial) {
            // Pi_ab = -alpha cbar mu_ab / rhobar_ab (physics_terms.hpp, ArtificialViscosity),
            // c_b = c0 (rho_b/rho0)^3 (Tait, gamma = 7).
            const double rb = rho_b * inv_rho0;
            const double cs_b = c0 * rb * rb * rb;
            pterm += -alpha * (0.5 * (cs_a + cs_b)) * mu / (0.5 * (rho_a + rho_b));
          }
          const double fp = -m_b * pterm * fr;
          // Lo & Shao (2002) laminar term, m_b 4 nu (r.gradW) / ((rho_a+rho_b)(r^2+eta^2)) v_ab.
          const double fv = VM == ViscosityModel::Laminar
                                ? m_b * nu4 * (r2 * fr) / (rho_a + rho_b) * inv_r2e
                                : 0.0;
          ac0 += fp * r0 + fv * w0;
          ac1 += fp * r1 + fv * w1;
          ac2 += fp * r2c + fv * w2;
          // Density diffusion between fluid particles: -2 coef drho_dyn (r.gradW)/(r^2+eta^2) V_b
          // with drho_dyn = (rho_b - rho_a) - rho0 g.(x_b - x_a)/c0^2 and g.(x_b-x_a) = -g.rab.
          const double drho_dyn = (rho_b - rho_a) + dd_hydro * grx;
          drho += fluid_b * dd_a * drho_dyn * (r2 * fr) * inv_r2e * (m_b / rho_b);
        }
        const double acc[3] = {ac0, ac1, ac2};
        out.drho[a] = drho;
        // A wall particle's `ace` is the force per unit mass the fluid exerts on it (no g).
        for (int d = 0; d < D; ++d) out.ace[a][d] = acc[d] + (fluid_a ? g[d] : 0.0);
        if (fluid_a) visc_dt_max = std::max(visc_dt_max, vdt);
      }
    }
  }
  out.visc_dt_max = visc_dt_max;
}

}  // namespace swell
