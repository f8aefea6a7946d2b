// The particle-pair driver, written once (STYLE.md): for every active particle a, gather its
// neighbours b (neighbours/gather.hpp, with the selection policy) and hand them to a pair
// evaluator (physics/wcsph_evaluator.hpp is the one the solver uses). Parallel over cells
// with OpenMP; each thread writes only the particles of its own cells, so there are no
// atomics and no scatter.
//
// Evaluator interface (all inline, no virtual calls):
//   using Centre = ...;                          what pass 2 needs of particle a
//   Centre centre(std::uint32_t a, bool fluid_a) const;
//   void pair(const Centre&, std::uint32_t entry, double& s0, double& s1, double& s2,
//             double& s3, double& mx) const;   one pair; entry = b | kWallBit for a wall b;
//                                              s0..s3 are sums, mx a maximum; a padding entry
//                                              (b == a) must contribute exactly nothing
//   double finish(std::uint32_t a, const Centre&, double s0, double s1, double s2, double s3,
//                 double mx);                  stores a's results, returns its share of the
//                                              run-wide maximum (e.g. the viscous dt signal)
//   void idle(std::uint32_t a);                  a in a skipped (dry) cell
// Each particle's sums run over its neighbours in a fixed order (the cell order), so results do
// not depend on the thread count.
#pragma once

#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/neighbours/gather.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

// One neighbour list per thread, reused across particles and steps (grows, never shrinks).
using NeighbourLists = std::vector<std::vector<std::uint32_t>>;

// Runs the evaluator over every active particle's neighbours within `support` (each thread on
// its own copy of it: evaluators are small values holding parameters and array pointers);
// returns the maximum of the values finish() returned (0 if none).
template <int D, class Select, class Evaluator>
double for_each_pair(const ParticleSet<D>& ps, const CellGrid<D>& grid, double support,
                     const Evaluator& ev, NeighbourLists& lists) {
  static_assert(sizeof(Vec<D>) == D * sizeof(double), "positions must be D packed doubles");
  const double support2 = support * support;
  const long ncells = static_cast<long>(grid.num_cells());
  const int nthreads = omp_get_max_threads();
  if (static_cast<int>(lists.size()) < nthreads) lists.resize(nthreads);
  const double* P = ps.pos.data()->data();
  const Role* role = ps.role.data();
  double run_max = 0.0;

#pragma omp parallel reduction(max : run_max)
  {
    // A private copy: its address never escapes, so the compiler keeps its parameters and
    // array pointers in registers across the SIMD loop instead of reloading them per pair
    // (the reduction stores could otherwise alias them): ~6 % on B3D.
    Evaluator local = ev;
    std::vector<std::uint32_t>& nbv = lists[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 16)
    for (long c = 0; c < ncells; ++c) {
      const std::uint32_t cb = grid.begin(c), ce = grid.end(c);
      if (cb == ce) continue;
      if (Select::kSkipDryCells && !grid.fluid_near(c)) {  // nothing to gather
        for (std::uint32_t a = cb; a < ce; ++a) local.idle(a);
        continue;
      }
      std::array<std::pair<std::uint32_t, std::uint32_t>, CellGrid<D>::kMaxRanges> ranges;
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
        double xa[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < D; ++d) xa[d] = P[a * D + d];
        const bool fluid_a = is_fluid(role[a]);
        // Pass 1: neighbour list.
        std::uint32_t k = 0;
        for (int r = 0; r < nr; ++r)
          k = gather_neighbours<D, Select>(P, role, xa, fluid_a, support2, ranges[r].first,
                                           ranges[r].second, nb, k);
        // Pad to a whole number of SIMD lanes with the particle itself: the evaluator gives a
        // coincident pair exactly zero, so the vector loop needs no scalar remainder.
        while (k % kPairLanes) nb[k++] = a;

        // Pass 2: pair terms in one SIMD loop (gathers, selects instead of branches).
        const typename Evaluator::Centre ca = local.centre(a, fluid_a);
        double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0, mx = 0.0;
#pragma omp simd reduction(+ : s0, s1, s2, s3) reduction(max : mx)
        for (std::uint32_t j = 0; j < k; ++j) local.pair(ca, nb[j], s0, s1, s2, s3, mx);
        run_max = std::max(run_max, local.finish(a, ca, s0, s1, s2, s3, mx));
      }
    }
  }
  return run_max;
}

}  // namespace swell
