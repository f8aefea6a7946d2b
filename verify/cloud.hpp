// Particle sets for the operator verifications: a lattice of n^D fluid particles filling
// [0, 1] x ... (the last axis up to `fill`), spacing dp = 1/n, each displaced by a uniform random
// vector of up to `jitter` dp per axis (a reproducible sequence from `seed`), V = dp^D (m = dp^D,
// rho = 1), and the cell grid sorted for it (cell = kernel support).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/state/particle_set.hpp"
#include "verify/verify.hpp"

namespace swell::verify {

template <int D>
struct Cloud {
  ParticleSet<D> ps;
  CellGrid<D> grid;
  double dp = 0.0, h = 0.0;
  // The visitor the operators of solver/physics/corrections.hpp take.
  auto near() const {
    return [this](const Vec<D>& x, auto&& fn) { grid.for_each_candidate_near(x, fn); };
  }
};

template <int D>
Cloud<D> make_cloud(int n, double h_over_dp, double support_factor, double jitter,
                    std::uint32_t seed, double fill = 1.0) {
  Cloud<D> c;
  c.dp = 1.0 / n;
  c.h = h_over_dp * c.dp;
  std::mt19937 rng(seed);
  // Uniform in [-1/2, 1/2) from the raw 32-bit output (the same sequence with every library).
  auto u = [&] { return static_cast<double>(rng()) / 4294967296.0 - 0.5; };
  const int n_last = static_cast<int>(std::lround(fill * n));
  long count = 1;
  for (int d = 0; d < D; ++d) count *= (d == D - 1 ? n_last : n);
  c.ps.reserve(static_cast<std::size_t>(count));
  const double m = std::pow(c.dp, D);
  for (long flat = 0; flat < count; ++flat) {
    Vec<D> x;
    long rest = flat;
    for (int d = 0; d < D; ++d) {
      const int side = d == D - 1 ? n_last : n;
      x[d] = (static_cast<double>(rest % side) + 0.5 + jitter * u()) * c.dp;
      rest /= side;
    }
    c.ps.add(x, Vec<D>::Zero(), 1.0, m, Role::Fluid, 0);
  }
  const double s = support_factor * c.h;
  c.grid = CellGrid<D>(Vec<D>::Constant(-s), Vec<D>::Constant(1.0 + s), s);
  c.grid.sort(c.ps);
  return c;
}

}  // namespace swell::verify
