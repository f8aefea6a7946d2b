// Cell-linked neighbour search.
//
// The domain is cut into cubic cells of the kernel support radius, padded by one empty cell on
// every side. sort() reorders the particles by cell (counting sort, x fastest) so the particles
// of one cell - and of three x-adjacent cells - are contiguous: a particle's neighbours are
// 3^(D-1) contiguous index ranges. Particles outside the domain or with non-finite state are
// moved past the active range (excluded) during the sort.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/state/particle_set.hpp"

namespace swell {

template <int D>
class CellGrid {
 public:
  struct SortResult {
    std::size_t out_of_domain = 0;
    std::size_t non_finite = 0;
  };

  CellGrid() = default;
  CellGrid(const Vec<D>& domain_min, const Vec<D>& domain_max, double cell_size)
      : min_(domain_min), max_(domain_max), cell_size_(cell_size), inv_cell_(1.0 / cell_size) {
    std::size_t total = 1;
    for (int d = 0; d < D; ++d) {
      if (!(domain_max[d] > domain_min[d]))
        throw std::invalid_argument("CellGrid: empty domain on axis " + std::to_string(d));
      n_[d] = static_cast<long>(std::floor((domain_max[d] - domain_min[d]) * inv_cell_)) + 3;
      total *= static_cast<std::size_t>(n_[d]);
    }
    if (total > (std::size_t{1} << 31))
      throw std::invalid_argument("CellGrid: domain too large for the cell size (" +
                                  std::to_string(total) + " cells)");
    num_cells_ = total;
    start_.assign(num_cells_ + 2, 0);
  }

  double cell_size() const { return cell_size_; }
  std::size_t num_cells() const { return num_cells_; }
  long cells(int axis) const { return n_[axis]; }
  const Vec<D>& domain_min() const { return min_; }
  const Vec<D>& domain_max() const { return max_; }

  bool inside_domain(const Vec<D>& x) const {
    for (int d = 0; d < D; ++d)
      if (!(x[d] >= min_[d] && x[d] <= max_[d])) return false;
    return true;
  }

  // Linear index of the cell holding x (x must be inside the domain).
  std::uint32_t cell_index(const Vec<D>& x) const {
    std::size_t c = 0, stride = 1;
    for (int d = 0; d < D; ++d) {
      const long i = static_cast<long>((x[d] - min_[d]) * inv_cell_) + 1;
      c += static_cast<std::size_t>(i) * stride;
      stride *= static_cast<std::size_t>(n_[d]);
    }
    return static_cast<std::uint32_t>(c);
  }

  // Reorders the active particles by cell and excludes the ones that left the domain or hold
  // non-finite values. Allocation-free once the buffers reached their size.
  SortResult sort(ParticleSet<D>& ps) {
    const std::size_t n = ps.size();
    const long ln = static_cast<long>(n);
    const auto excluded_cell = static_cast<std::uint32_t>(num_cells_);
    cell_of_.resize(n);
    std::size_t non_finite = 0, out_of_domain = 0;
#pragma omp parallel for schedule(static) reduction(+ : non_finite, out_of_domain) \
    if (ln > ParticleSet<D>::kParallelMin)
    for (long i = 0; i < ln; ++i) {
      const bool finite =
          ps.pos[i].allFinite() && ps.vel[i].allFinite() && std::isfinite(ps.rho[i]);
      if (!finite) {
        cell_of_[i] = excluded_cell;
        ++non_finite;
      } else if (!inside_domain(ps.pos[i])) {
        cell_of_[i] = excluded_cell;
        ++out_of_domain;
      } else {
        cell_of_[i] = cell_index(ps.pos[i]);
      }
    }
    SortResult result;
    result.non_finite = non_finite;
    result.out_of_domain = out_of_domain;
    // Counting sort: start_[c] becomes the first index of cell c. The histogram and the
    // scatter are serial (a few ns per particle); the gathers below are parallel.
    std::fill(start_.begin(), start_.end(), 0u);
    for (std::size_t i = 0; i < n; ++i) ++start_[cell_of_[i] + 1];
    for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
    order_.resize(n);
    cursor_.assign(start_.begin(), start_.end());
    for (std::size_t i = 0; i < n; ++i)
      order_[cursor_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
    ps.permute(order_);
    ps.n_active = start_[num_cells_];
    // Cell ids in the new order (from the counting sort, no second cell computation) and the
    // cells holding fluid: wall cells with no fluid around them can skip the pair loop.
    has_fluid_.resize(num_cells_);
    const long ncells = static_cast<long>(num_cells_);
#pragma omp parallel for schedule(static) if (ln > ParticleSet <D>::kParallelMin)
    for (long c = 0; c < ncells; ++c) {
      std::uint8_t any = 0;
      for (std::uint32_t i = start_[c]; i < start_[c + 1]; ++i) {
        cell_of_[i] = static_cast<std::uint32_t>(c);
        any |= ps.role[i] == Role::Fluid;
      }
      has_fluid_[c] = any;
    }
    for (std::uint32_t i = start_[num_cells_]; i < start_[num_cells_ + 1]; ++i)
      cell_of_[i] = excluded_cell;
    return result;
  }

  // Index range [begin, end) of the particles in cell c (valid after sort()).
  std::uint32_t begin(std::size_t c) const {
    return start_[c];
  }
  std::uint32_t end(std::size_t c) const {
    return start_[c + 1];
  }
  std::uint32_t cell_of(std::size_t i) const {
    return cell_of_[i];
  }

  // Calls fn(begin, end) for the 3^(D-1) contiguous index ranges covering the 3^D cells around
  // cell c. c must be an interior cell (any cell holding an active particle is).
  template <class Fn>
  void for_each_neighbour_range(std::size_t c, Fn&& fn) const {
    for_each_neighbour_row(c, [&](std::size_t row) { fn(start_[row - 1], start_[row + 2]); });
  }

  // Calls fn(row) with the middle cell of each of the 3^(D-1) x-rows around cell c.
  template <class Fn>
  void for_each_neighbour_row(std::size_t c, Fn&& fn) const {
    const long nx = n_[0];
    if constexpr (D == 1) {
      fn(c);
    } else if constexpr (D == 2) {
      for (long dy = -1; dy <= 1; ++dy)
        fn(static_cast<std::size_t>(static_cast<long>(c) + dy * nx));
    } else {
      const long nxy = nx * n_[1];
      for (long dz = -1; dz <= 1; ++dz)
        for (long dy = -1; dy <= 1; ++dy)
          fn(static_cast<std::size_t>(static_cast<long>(c) + dz * nxy + dy * nx));
    }
  }

  // True if any of the 3^D cells around interior cell c holds a fluid particle.
  bool fluid_near(std::size_t c) const {
    bool any = false;
    for_each_neighbour_row(c, [&](std::size_t row) {
      any = any || has_fluid_[row - 1] || has_fluid_[row] || has_fluid_[row + 1];
    });
    return any;
  }

  // Calls fn(j) for every candidate neighbour j of active particle i (including i itself);
  // the caller filters by distance. Convenience for tests and gauges, not the hot loop.
  template <class Fn>
  void for_each_candidate(std::size_t i, Fn&& fn) const {
    for_each_neighbour_range(cell_of_[i], [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t j = b; j < e; ++j) fn(j);
    });
  }

  // Same for an arbitrary point inside the domain (probes).
  template <class Fn>
  void for_each_candidate_near(const Vec<D>& x, Fn&& fn) const {
    if (!inside_domain(x)) return;
    for_each_neighbour_range(cell_index(x), [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t j = b; j < e; ++j) fn(j);
    });
  }

 private:
  Vec<D> min_ = Vec<D>::Zero(), max_ = Vec<D>::Zero();
  double cell_size_ = 1.0, inv_cell_ = 1.0;
  std::array<long, D> n_{};
  std::size_t num_cells_ = 0;
  std::vector<std::uint32_t> start_, cursor_, order_, cell_of_;
  std::vector<std::uint8_t> has_fluid_;
};

}  // namespace swell
