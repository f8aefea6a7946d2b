// The particle-pair driver, written once (the SIMD pair loop of the forces and of shifting's first
// pass): for every active particle a, gather its neighbours b (neighbours/gather.hpp, with the
// selection policy) and hand them to a pair evaluator (physics/wcsph_evaluator.hpp is the one the
// solver uses). Parallel over cells with OpenMP; each thread writes only the particles of its own
// cells, so there are no atomics and no scatter.
//
// Evaluator interface (all inline, no virtual calls):
//   using Real = ...;                            the pair terms' arithmetic type (double/float)
//   using Centre = ...;                          what pass 2 needs of particle a
//   Centre centre(std::uint32_t a, bool fluid_a) const;
//   void pair(const Centre&, std::uint32_t entry, Real& s0, Real& s1, Real& s2,
//             Real& s3, Real& mx) const;   one pair; entry = b | kWallBit for a wall b;
//                                              s0..s3 are sums, mx a maximum; a padding entry
//                                              (b == a) must contribute exactly nothing
//   double finish(std::uint32_t a, const Centre&, Real s0, Real s1, Real s2, Real s3,
//                 Real mx);                  stores a's results, returns its share of the
//                                              run-wide maximum (e.g. the viscous dt signal)
//   void idle(std::uint32_t a);                  a in a skipped (dry) cell
// Optional, for a float evaluator (the WCSPH one): `static constexpr bool kStaged = true;`, a
// `Lanes` type, `void stage(const std::uint32_t* entries, Lanes&) const` that copies 16
// entries' values into lane arrays, and `pair_lane(centre, entry, lanes, lane, sums...)`, the
// same terms as pair() from them; the driver then stages each block of 16 before the SIMD loop.
// Each particle's sums run over its neighbours in a fixed order (the cell order), so results do
// not depend on the thread count.
#pragma once

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/neighbours/gather.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

// The driver's reusable scratch (grows, never shrinks): one neighbour list per thread and, for
// an evaluator whose arithmetic is float, the float copy of the positions its gather tests.
struct NeighbourLists {
  std::vector<std::vector<std::uint32_t>> lists;
  std::vector<float> pos;  // (x - origin) rounded to float, D per stored particle
  // Each thread's range of cells (for_each_pair): the next chunk to take, by its owner and
  // then by threads that finished their own, and the end; one cache line each.
  struct alignas(64) Range {
    std::atomic<long> next{0};
    long end = 0;
  };
  std::unique_ptr<Range[]> ranges;
  int n_ranges = 0;
};

// Hands out the cells of the threads' ranges in chunks: first the calling thread's own range,
// then the others' in turn. next() returns the next cell, or -1 when every range is done.
class CellChunks {
 public:
  static constexpr long kChunk = 16;
  CellChunks(NeighbourLists::Range* ranges, int n, int own) : ranges_(ranges), n_(n), own_(own) {}
  long next() {
    if (c_ < end_) return c_++;
    while (k_ < n_) {
      NeighbourLists::Range& r = ranges_[(own_ + k_) % n_];
      const long c0 = r.next.fetch_add(kChunk, std::memory_order_relaxed);
      if (c0 < r.end) {
        c_ = c0 + 1;
        end_ = std::min(c0 + kChunk, r.end);
        return c0;
      }
      ++k_;
    }
    return -1;
  }

 private:
  NeighbourLists::Range* ranges_;
  int n_, own_, k_ = 0;
  long c_ = 0, end_ = 0;
};

// The margin the float gather adds to the support: the copy rounds each coordinate by at most
// X 2^-24 (X: the largest |x - origin|), so a difference is off by 2 X 2^-24 per axis plus its
// own rounding, and r^2 by a few roundings more: twice that bound for the coordinates' part,
// several times for the rest, so no pair inside the support is ever dropped (the evaluator
// zeroes the few admitted beyond it).
inline double float_gather_margin(int dims, double extent, double support) {
  return (4.0 * std::sqrt(static_cast<double>(dims)) * extent + 16.0 * support) * 0x1p-24;
}

// Runs the evaluator over every active particle's neighbours within `support` (each thread on
// its own copy of it: evaluators are small values holding parameters and array pointers);
// returns the maximum of the values finish() returned (0 if none).
template <int D, class Select, class Evaluator>
double for_each_pair(const ParticleSet<D>& ps, const CellGrid<D>& grid, double support,
                     const Evaluator& ev, NeighbourLists& lists) {
  static_assert(sizeof(Vec<D>) == D * sizeof(double), "positions must be D packed doubles");
  const double support2 = support * support;
  const int nthreads = omp_get_max_threads();
  if (static_cast<int>(lists.lists.size()) < nthreads) lists.lists.resize(nthreads);
  const double* P = ps.pos.data()->data();
  const Role* role = ps.role.data();
  double run_max = 0.0;
  // A float evaluator gathers on a float copy of the positions, relative to the grid's lower
  // corner (periodic and halo images lie within a support of the domain).
  constexpr bool kFloatGather = std::is_same_v<typename Evaluator::Real, float>;
  // An evaluator that stages each block of 16 neighbours' values itself (stage, pair_lane).
  constexpr bool kStaged = [] {
    if constexpr (requires { Evaluator::kStaged; })
      return Evaluator::kStaged && kFloatGather;
    else
      return false;
  }();
  const Vec<D> origin = grid.domain_min();
  float support2f = 0.0f;
  if constexpr (kFloatGather) {
    const std::size_t ns = ps.stored();
    if (lists.pos.size() < ns * D) lists.pos.resize(ns * D + ns * D / 8);  // rare, amortised
    float* F = lists.pos.data();
    // Candidates are active particles (inside the domain) and images (within a cell of it).
    const double extent = (grid.domain_max() - origin).maxCoeff() + 2.0 * grid.cell_size();
    const double s = support + float_gather_margin(D, extent, support);
    support2f = static_cast<float>(s * s);
    // Active particles and images only: the excluded ones (between them) are never candidates
    // and may hold values float cannot represent.
    const long na = static_cast<long>(ps.size()), gb = static_cast<long>(ps.ghost_begin());
#pragma omp parallel for schedule(static)
    for (long i = 0; i < static_cast<long>(ns); ++i) {
      if (i >= na && i < gb) continue;
      for (int d = 0; d < D; ++d) F[i * D + d] = static_cast<float>(P[i * D + d] - origin[d]);
    }
  }
  const float* F = lists.pos.data();

  // Each thread starts on the cells of the particles the static particle loops give it
  // (CellGrid::thread_cells), so a step's data stays in one core's cache (a dynamic schedule
  // hands cells to either thread: on two vCPUs on different host dies that made every
  // particle loop of the step 2-3x slower here). A thread done with its own range helps with
  // the others' (CellChunks), so a slower or descheduled core does not hold the step up.
  if (lists.n_ranges < nthreads) {  // once
    lists.ranges = std::make_unique<NeighbourLists::Range[]>(nthreads);
    lists.n_ranges = nthreads;
  }
  NeighbourLists::Range* ranges = lists.ranges.get();
  for (int t = 0; t < nthreads; ++t) {
    long first = 0, last = 0;
    grid.thread_cells(t, nthreads, first, last);
    ranges[t].next.store(first, std::memory_order_relaxed);
    ranges[t].end = last;
  }
#pragma omp parallel num_threads(nthreads) reduction(max : run_max)
  {
    // A private copy: its address never escapes, so the compiler keeps its parameters and
    // array pointers in registers across the SIMD loop instead of reloading them per pair
    // (the reduction stores could otherwise alias them): ~6 % on B3D.
    Evaluator local = ev;
    std::vector<std::uint32_t>& nbv = lists.lists[omp_get_thread_num()];
    // The cell order never matters: each particle's sums run over its neighbours in a fixed
    // order, whichever thread takes its cell.
    CellChunks chunks(ranges, nthreads, omp_get_thread_num());
    for (long c = chunks.next(); c >= 0; c = chunks.next()) {
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
      // Room for the 16-entry stores of the float gather and the padding.
      if (nbv.size() < candidates + 2 * kPairLanes)
        nbv.resize(candidates + candidates / 2 + 2 * kPairLanes);  // rare, amortised
      std::uint32_t* nb = nbv.data();

      for (std::uint32_t a = cb; a < ce; ++a) {
        const bool fluid_a = is_fluid(role[a]);
        // Pass 1: neighbour list.
        std::uint32_t k = 0;
        if constexpr (kFloatGather) {
          float xa[3] = {0.0f, 0.0f, 0.0f};
          for (int d = 0; d < D; ++d) xa[d] = F[a * D + d];
          for (int r = 0; r < nr; ++r)
            k = gather_neighbours<D, Select>(F, role, xa, fluid_a, support2f, ranges[r].first,
                                             ranges[r].second, nb, k);
        } else {
          double xa[3] = {0.0, 0.0, 0.0};
          for (int d = 0; d < D; ++d) xa[d] = P[a * D + d];
          for (int r = 0; r < nr; ++r)
            k = gather_neighbours<D, Select>(P, role, xa, fluid_a, support2, ranges[r].first,
                                             ranges[r].second, nb, k);
        }
        // Pad to a whole number of SIMD lanes with the particle itself: the evaluator gives a
        // coincident pair exactly zero, so the vector loop needs no scalar remainder (16 lanes
        // for a float evaluator: with 8, 2D lists of ~25 neighbours spent ~40 % of the loop's
        // time in the remainder's scalar code).
        constexpr std::uint32_t kLanes = kFloatGather ? 2 * kPairLanes : kPairLanes;
        while (k % kLanes) nb[k++] = a;

        // Pass 2: pair terms in one SIMD loop (staged lanes or indexed loads; selects instead
        // of branches).
        const typename Evaluator::Centre ca = local.centre(a, fluid_a);
        using Real = typename Evaluator::Real;  // the sums' type
        if constexpr (kFloatGather) {
          // Lane sums of our own, added up in GCC's reduction order by one transpose
          // (gather.hpp): the same bits as `omp simd reduction`, without its scalar epilogue.
          alignas(64) float q0[16], q1[16], q2[16], q3[16], qm[16];
          for (int l = 0; l < 16; ++l) q0[l] = q1[l] = q2[l] = q3[l] = qm[l] = 0.0f;
          if constexpr (kStaged) {
            typename Evaluator::Lanes lanes;
            for (std::uint32_t j = 0; j < k; j += 16) {
              local.stage(nb + j, lanes);
#pragma omp simd
              for (std::uint32_t l = 0; l < 16; ++l)
                local.pair_lane(ca, nb[j + l], lanes, l, q0[l], q1[l], q2[l], q3[l], qm[l]);
            }
          } else {
            for (std::uint32_t j = 0; j < k; j += 16) {
#pragma omp simd
              for (std::uint32_t l = 0; l < 16; ++l)
                local.pair(ca, nb[j + l], q0[l], q1[l], q2[l], q3[l], qm[l]);
            }
          }
          float s[4];
          sum_lanes_in_order(q0, q1, q2, q3, s);
          float mx = 0.0f;  // a maximum: the same whatever the order
          for (int l = 0; l < 16; ++l) mx = std::max(mx, qm[l]);
          run_max = std::max(run_max, local.finish(a, ca, s[0], s[1], s[2], s[3], mx));
        } else {
          Real s0 = 0, s1 = 0, s2 = 0, s3 = 0, mx = 0;
#pragma omp simd reduction(+ : s0, s1, s2, s3) reduction(max : mx)
          for (std::uint32_t j = 0; j < k; ++j) local.pair(ca, nb[j], s0, s1, s2, s3, mx);
          run_max = std::max(run_max, local.finish(a, ca, s0, s1, s2, s3, mx));
        }
      }
    }
  }
  return run_max;
}

}  // namespace swell
