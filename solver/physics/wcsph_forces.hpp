// One force evaluation of the WCSPH equations: the EoS per particle (P/rho^2 and c), then the
// pair driver with the WCSPH evaluator. The kernel and the viscosity model are chosen here at
// run time (with_kernel), the selection policy by the caller (the boundary model, bc/): the
// three compile-time switches of the pair loop. The viscosity switch has three values:
// artificial with the Tait gamma = 7 signal speed computed in the loop, artificial with c from
// the EoS buffer (any other gamma), laminar.
#pragma once

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/neighbours/pair_driver.hpp"
#include "solver/physics/eos.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/physics/wcsph_evaluator.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

// Derived per-evaluation values (never checkpointed: recomputed from the state).
template <int D>
struct ForceBuffers {
  std::vector<Vec<D>> ace;
  std::vector<double> drho;
  std::vector<double> prs;  // P_a / rho_a^2 (between steps: P_a, on request, Simulation::pressure)
  std::vector<double> cs;   // sound speed c_a, only where the pair loop reads it
  // 2D float pair loop: (v_x, v_y, rho, P/rho^2) of each particle in float, one 16-byte row
  // the loop stages from (WcsphEvaluator::kStaged); empty otherwise.
  std::vector<float> rows;
  double visc_dt_max = 0.0;  // max over pairs of h |v_ab.r_ab| / (r^2 + eta^2), for dt
  double cs_max = 0.0;
  bool one_mass = false;  // every stored particle has the same mass (compute_pressure)
  NeighbourLists neighbours;

  // At least n entries in each of the rates' buffers. Capacity grows with 1/8 headroom, since
  // the number of periodic or halo images changes from one evaluation to the next; the sizes
  // differ between the buffers after a reorder lent them as scratch (ParticleSet::permute).
  void resize(std::size_t n) {
    grow(ace, n);
    grow(drho, n);
    grow(prs, n);
    if constexpr (kRows) grow(rows, 4 * n);
  }
  static constexpr bool kRows = D == 2 && std::is_same_v<PairReal, float>;

 private:
  template <class T>
  static void grow(std::vector<T>& a, std::size_t n) {
    if (a.size() >= n) return;
    if (a.capacity() < n) a.reserve(n + n / 8);
    a.resize(n);
  }
};

// P/rho^2 of every active particle and periodic image, c too where the loop reads it (with_cs), and
// the largest sound speed (for dt).
template <int D>
void compute_pressure(const ParticleSet<D>& ps, const TaitEos& eos, ForceBuffers<D>& out,
                      bool with_cs = true) {
  const long n = static_cast<long>(ps.size());
  double rho_max = 0.0;
  if (with_cs && out.cs.size() < ps.stored()) out.cs.resize(ps.stored());  // once
  constexpr bool kRows = ForceBuffers<D>::kRows;
  if constexpr (kRows) {
    if (out.rows.size() < 4 * ps.stored()) out.resize(ps.stored());  // rare, amortised
  }
  float* rows = out.rows.data();
  auto one = [&](std::size_t i) {
    const double rho = ps.rho[i];
    out.prs[i] = eos.pressure(rho) / (rho * rho);
    if (with_cs) out.cs[i] = eos.sound_speed(rho);
    if constexpr (kRows) {
      rows[4 * i] = static_cast<float>(ps.vel[i][0]);
      rows[4 * i + 1] = static_cast<float>(ps.vel[i][1]);
      rows[4 * i + 2] = static_cast<float>(ps.rho[i]);
      rows[4 * i + 3] = static_cast<float>(out.prs[i]);
    }
  };
  // One mass for every particle (the lattice fill's) makes the mass a constant in the pair
  // terms: checked here, in the parallel pass, rather than by a serial one over all particles.
  const std::size_t stored = ps.stored();
  const double m0 = stored > 0 ? ps.mass[0] : 0.0;
  int differs = 0;
#pragma omp parallel for schedule(static) reduction(max : rho_max) reduction(| : differs)
  for (long i = 0; i < n; ++i) {
    one(static_cast<std::size_t>(i));
    rho_max = std::max(rho_max, static_cast<double>(ps.rho[i]));
    differs |= ps.mass[i] != m0;
  }
  // Periodic images: the same values as their sources (their densities are copies).
  for (std::size_t i = ps.ghost_begin(); i < stored; ++i) one(i);
  for (std::size_t i = static_cast<std::size_t>(n); i < stored; ++i) differs |= ps.mass[i] != m0;
  out.one_mass = stored > 0 && !differs;
  out.cs_max = eos.sound_speed(rho_max);  // c grows with rho
}

// drho/dt and dv/dt of every active particle at the current state (the grid must be sorted).
template <int D, class Select>
void compute_forces(const ParticleSet<D>& ps, const CellGrid<D>& grid, const SolverParams& prm,
                    const TaitEos& eos, ForceBuffers<D>& f) {
  // The buffer is read only by artificial viscosity with a Tait exponent other than 7.
  const bool tait7 = prm.gamma == 7.0;
  compute_pressure(ps, eos, f, prm.viscosity == ViscosityModel::Artificial && !tait7);
  with_kernel<D>(prm.kernel, prm.h, [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    auto run = [&](auto ev) {
      f.visc_dt_max = for_each_pair<D, Select>(ps, grid, kernel.support(), ev, f.neighbours);
    };
    const bool one_mass = f.one_mass;  // from compute_pressure
    if (prm.viscosity == ViscosityModel::Artificial && tait7 && one_mass)
      run(WcsphEvaluator<D, K, ViscosityModel::Artificial, Select, true, true>(
          ps, prm, kernel, f.prs.data(), f.cs.data(), f.drho.data(), f.ace.data(), f.rows.data()));
    else if (prm.viscosity == ViscosityModel::Artificial && tait7)
      run(WcsphEvaluator<D, K, ViscosityModel::Artificial, Select, true>(
          ps, prm, kernel, f.prs.data(), f.cs.data(), f.drho.data(), f.ace.data(), f.rows.data()));
    else if (prm.viscosity == ViscosityModel::Artificial)
      run(WcsphEvaluator<D, K, ViscosityModel::Artificial, Select>(
          ps, prm, kernel, f.prs.data(), f.cs.data(), f.drho.data(), f.ace.data(), f.rows.data()));
    else
      run(WcsphEvaluator<D, K, ViscosityModel::Laminar, Select>(
          ps, prm, kernel, f.prs.data(), f.cs.data(), f.drho.data(), f.ace.data(), f.rows.data()));
    return 0;
  });
}

}  // namespace swell
