// Cell-linked neighbour search.
//
// The domain is cut into cubic cells of the kernel support radius, padded by one empty cell on
// every side. sort() reorders the particles by cell (counting sort, x fastest) so the particles
// of one cell - and of three x-adjacent cells - are contiguous: a particle's neighbours are
// 3^(D-1) contiguous index ranges. Particles outside the domain or with non-finite state are
// moved past the active range (excluded) during the sort.
//
// Periodic axes (set_periodic): the domain's extent on such an axis is the period L. The sort
// wraps particles that crossed a periodic face back into [min, max) and then appends periodic
// images - copies of the particles within one cell (one kernel support) of a periodic face,
// shifted by +-L, corners included - after the stored particles (ParticleSet::n_ghost). The
// images fall in the padding cells; they are counted into cells of their own (ghost_start_),
// and each x-row's neighbour ranges gain the matching range of images, so the pair loop, the
// shifting pass and the point interpolations read them like any neighbour without knowing.
// Images are never centres of the pair loop. drop_ghosts() removes them (the Simulation does
// at the end of every step); refresh_ghosts() copies their sources' state again after a stage
// changed it. With no periodic axis none of this runs and the sort is as before.
//
// Remote images (domain decomposition, solver/time/exchange.hpp) take the same path: the
// exchange asks place_remote_images() where each arriving particle goes in the image block,
// stores it there and calls attach_remote_images(). Such an image has no local source
// (ghost_source() is kRemote); refresh_ghosts() leaves it to the exchange. In a decomposed run
// with periodic axes (set_images_by_exchange) sort() builds no images: place_remote_images()
// adds this rank's own periodic images on every periodic axis but the slab axis (the exchange
// sends the images across the slab axis's periodic faces, and the halo particles' images on
// the other axes), ordered by cell together with the remote ones.
#pragma once

#include <omp.h>

#include <algorithm>
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

  // Makes the given axes periodic with period domain_max - domain_min. An image lies within
  // one cell of a face, so the period must span at least two cells.
  void set_periodic(const std::array<bool, D>& axes) {
    any_periodic_ = false;
    for (int d = 0; d < D; ++d) {
      periodic_[d] = axes[d];
      if (!axes[d]) continue;
      any_periodic_ = true;
      if (max_[d] - min_[d] < 2.0 * cell_size_)
        throw std::invalid_argument("CellGrid: the periodic extent on axis " + std::to_string(d) +
                                    " (" + std::to_string(max_[d] - min_[d]) +
                                    " m) must be at least two kernel supports (" +
                                    std::to_string(2.0 * cell_size_) + " m)");
    }
  }
  bool periodic(int axis) const { return periodic_[axis]; }
  bool any_periodic() const { return any_periodic_; }
  // A decomposed run: the images are built with the halo (place_remote_images), not by sort().
  void set_images_by_exchange(bool on) { by_exchange_ = on; }
  // Wraps the particles that crossed a periodic face (sort() does it too; a decomposed run does
  // it before migration, so each particle goes to the rank that owns its wrapped position).
  void wrap_periodic(ParticleSet<D>& ps) const {
    if (any_periodic_) wrap(ps);
  }
  // The periodic axes (but skip_axis) within one cell of whose faces x lies, as a bit mask, and
  // the shift to its image across each: s[d] = +L near the low face, -L near the high one.
  int image_shifts(const Vec<D>& x, int skip_axis, std::array<double, D>& s) const {
    int axes = 0;
    for (int d = 0; d < D; ++d) {
      if (!periodic_[d] || d == skip_axis) continue;
      const double L = max_[d] - min_[d];
      if (x[d] - min_[d] < cell_size_)
        s[d] = L;
      else if (max_[d] - x[d] < cell_size_)
        s[d] = -L;
      if (s[d] != 0.0) axes |= 1 << d;
    }
    return axes;
  }
  // Whether some images have their source on this rank (periodic images; refresh_ghosts).
  bool has_local_images() const { return n_local_images_ > 0; }
  std::size_t ghost_count() const { return n_ghost_; }
  // Source (an active index) and cell of image k, stored at ParticleSet::ghost_begin() + k.
  // kRemote for a remote image (its source lives on another rank).
  std::uint32_t ghost_source(std::size_t k) const { return ghost_src_[k]; }
  static constexpr std::uint32_t kRemote = 0xffffffffu;
  std::uint32_t ghost_cell(std::size_t k) const { return ghost_cell_[k]; }

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

  // How sort() rearranges the particle arrays: with the set's own scratch (default), with
  // arrays the caller lends as scratch (ParticleSet::permute), or in place without scratch
  // (ParticleSet::permute_in_place; the `follow` arrays, indexed like the particles, are
  // rearranged alike).
  struct Reorder {
    LentScratch<D> lent;
    bool in_place = false;
    std::vector<Vec<D>>* follow_vec = nullptr;
    std::vector<double>* follow_dbl = nullptr;
  };

  // Reorders the active particles by cell and excludes the ones that left the domain or hold
  // non-finite values. Allocation-free once the buffers reached their size.
  SortResult sort(ParticleSet<D>& ps, const Reorder& how = {}) {
    drop_ghosts(ps);
    if (any_periodic_) wrap(ps);
    const std::size_t n = ps.size();
    const long ln = static_cast<long>(n);
    const auto excluded_cell = static_cast<std::uint32_t>(num_cells_);
    cell_of_.resize(n);
    order_.resize(n);
    std::size_t non_finite = 0, out_of_domain = 0;
    const int max_threads = omp_get_max_threads();
    if (static_cast<int>(counts_.size()) < max_threads) {  // once
      counts_.resize(max_threads);
      cursors_.resize(max_threads);
      count_range_.resize(max_threads);
    }
    // A stable counting sort by cell in one parallel region, each thread on the particles
    // schedule(static) gives it (thread_cells): its cell ids and a histogram of its own over the
    // cells its particles fall in (a narrow range: the particles were sorted a step ago), the
    // cell starts summed by one thread, then each thread scatters its particles after the
    // earlier threads' ones in every cell. The order is the serial sort's (within a cell by
    // index). start_[c] becomes the first index of cell c.
#pragma omp parallel reduction(+ : non_finite, out_of_domain) if (ln > ParticleSet <D>::kParallelMin)
    {
      const int t = omp_get_thread_num(), nt = omp_get_num_threads();
      const std::size_t q = n / nt, r = n % nt;
      const std::size_t i0 = t * q + std::min<std::size_t>(t, r),
                        i1 = i0 + q + (t < static_cast<int>(r));
      std::uint32_t lo = excluded_cell, hi = 0;
      for (std::size_t i = i0; i < i1; ++i) {
        const bool finite =
            ps.pos[i].allFinite() && ps.vel[i].allFinite() && std::isfinite(ps.rho[i]);
        std::uint32_t c = excluded_cell;
        if (!finite)
          ++non_finite;
        else if (!inside_domain(ps.pos[i]))
          ++out_of_domain;
        else
          c = static_cast<std::uint32_t>(cell_index(ps.pos[i]));
        cell_of_[i] = c;
        lo = std::min(lo, c);
        hi = std::max(hi, c);
      }
      // The thread's histogram and cursors over its cells [lo, hi] (grown rarely, amortised).
      const std::size_t span = lo <= hi ? hi - lo + 1 : 0;
      if (counts_[t].size() < span) {
        counts_[t].resize(span + span / 2);
        cursors_[t].resize(span + span / 2);
      }
      std::uint32_t* cnt = counts_[t].data();  // cell lo + k at k
      std::fill(cnt, cnt + span, 0u);
      for (std::size_t i = i0; i < i1; ++i) ++cnt[cell_of_[i] - lo];
      count_range_[t] = {lo, hi};
#pragma omp barrier
#pragma omp single
      {  // O(cells + the threads' spans): each histogram added over its own range only
        std::fill(start_.begin(), start_.end(), 0u);
        for (int u = 0; u < nt; ++u)
          for (std::uint32_t c = count_range_[u][0]; c <= count_range_[u][1]; ++c)
            start_[c + 1] += counts_[u][c - count_range_[u][0]];
        for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
      }
      // Cursors: the cell's start plus the earlier threads' particles in it (where their
      // ranges overlap this thread's: only near the range ends, the particles being sorted).
      std::uint32_t* cur = cursors_[t].data();  // cell lo + k at k
      for (std::size_t k = 0; k < span; ++k) cur[k] = start_[lo + k];
      for (int u = 0; u < t; ++u) {
        const std::uint32_t a = std::max(lo, count_range_[u][0]),
                            b = std::min(hi, count_range_[u][1]);
        for (std::uint32_t c = a; c <= b && span > 0; ++c)
          cur[c - lo] += counts_[u][c - count_range_[u][0]];
      }
      for (std::size_t i = i0; i < i1; ++i)
        order_[cur[cell_of_[i] - lo]++] = static_cast<std::uint32_t>(i);
    }
    SortResult result;
    result.non_finite = non_finite;
    result.out_of_domain = out_of_domain;
    if (how.in_place) {
      ps.permute_in_place(order_, how.follow_vec, how.follow_dbl);
    } else {
      // The cell ids are rebuilt below from the counting sort: until then they are the
      // reorder's uint32 scratch.
      LentScratch<D> lent = how.lent;
      lent.u32 = &cell_of_;
      ps.permute(order_, lent);
    }
    ps.n_active = start_[num_cells_];
    // Cell ids in the new order (from the counting sort, no second cell computation) and the
    // cells holding fluid: wall cells with no fluid around them can skip the pair loop.
    has_fluid_.resize(num_cells_);
    const long ncells = static_cast<long>(num_cells_);
#pragma omp parallel if (ln > ParticleSet <D>::kParallelMin)
    {
      long c0 = 0, c1 = ncells;
      thread_cells(omp_get_thread_num(), omp_get_num_threads(), c0, c1);
      for (long c = c0; c < c1; ++c) {
        std::uint8_t any = 0;
        for (std::uint32_t i = start_[c]; i < start_[c + 1]; ++i) {
          cell_of_[i] = static_cast<std::uint32_t>(c);
          any |= ps.role[i] == Role::Fluid;
        }
        has_fluid_[c] = any;
      }
    }
    for (std::uint32_t i = start_[num_cells_]; i < start_[num_cells_ + 1]; ++i)
      cell_of_[i] = excluded_cell;
    if (any_periodic_ && !by_exchange_) build_ghosts(ps);
    return result;
  }

  // Removes the periodic images (allocation-free: the arrays keep their capacity).
  void drop_ghosts(ParticleSet<D>& ps) {
    n_ghost_ = 0;
    n_local_images_ = 0;
    if (ps.n_ghost == 0) return;
    const std::size_t keep = ps.total();
    ps.for_each_field([&](const FieldInfo& f, auto& a) {
      if (ps.enabled(f)) a.resize(keep);
    });
    ps.n_ghost = 0;
  }

  // Copies position (shifted), velocity and density from each image's source again: after a
  // stage changed the sources (a boundary model's wall densities, a density re-initialisation,
  // the integration before the after_integration hooks).
  void refresh_ghosts(ParticleSet<D>& ps) const {
    const std::size_t base = ps.ghost_begin();
    for (std::size_t k = 0; k < n_ghost_; ++k) {
      const std::uint32_t src = ghost_src_[k];
      if (src == kRemote) continue;  // the exchange refreshes it
      ps.pos[base + k] = ps.pos[src] + ghost_shift_[k];
      ps.vel[base + k] = ps.vel[src];
      ps.rho[base + k] = ps.rho[src];
    }
  }

  // Remote images (after sort()): the arriving particles at positions xs get slots in the image
  // block, ordered by cell together with this rank's own periodic images on the periodic axes
  // other than `slab_axis` (none without periodic axes). Every field grows by all the images
  // and the periodic ones are stored; remote image k must then be stored at
  // B + slot_of[k], B being the arrays' size before this call, and attach_remote_images()
  // marks their cells and sets ps.n_ghost. Allocation-free once the buffers reached their size.
  void place_remote_images(ParticleSet<D>& ps, const std::vector<Vec<D>>& xs,
                           std::vector<std::uint32_t>& slot_of, int slab_axis = -1) {
    if (ps.n_ghost != 0 || (any_periodic_ && !by_exchange_))
      throw std::logic_error("CellGrid: remote images on a grid that built its own images");
    if (any_periodic_)
      collect_images(ps, slab_axis);
    else
      cand_src_.clear(), cand_shift_.clear(), cand_cell_.clear();
    n_local_images_ = cand_src_.size();
    for (const Vec<D>& x : xs) {
      cand_src_.push_back(kRemote);
      cand_shift_.push_back(Vec<D>::Zero());
      cand_cell_.push_back(ghost_cell_index(x));
    }
    store_images(ps, &slot_of);
  }
  void attach_remote_images(ParticleSet<D>& ps) {
    if (ps.pos.size() != ghost_base_ + n_ghost_ || ps.n_ghost != 0)
      throw std::logic_error("CellGrid: the remote images are not stored where they were placed");
    for (std::size_t k = 0; k < n_ghost_; ++k)
      has_fluid_[ghost_cell_[k]] |= ps.role[ghost_base_ + k] == Role::Fluid;
    ps.n_ghost = n_ghost_;
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

  // The cells [first, last) of thread t of nt: those whose first particle lies in the share of
  // the active particles that OpenMP's schedule(static) gives thread t of nt (libgomp: the
  // first n % nt threads take one more). Cell loops split this way touch the particles the
  // particle loops (schedule(static)) give the same thread, so a step's data stays in that
  // core's cache instead of crossing to the other's (two vCPUs on different host dies here
  // take 3-5x longer per cache-line transfer than on one).
  void thread_cells(int t, int nt, long& first, long& last) const {
    const std::size_t n = start_[num_cells_], q = n / nt, r = n % nt;
    auto split = [&](std::size_t k) { return k * q + std::min(k, r); };
    auto cell_at = [&](std::size_t i) {
      return static_cast<long>(std::lower_bound(start_.begin(), start_.begin() + num_cells_, i) -
                               start_.begin());
    };
    first = t == 0 ? 0 : cell_at(split(t));
    last = t + 1 == nt ? static_cast<long>(num_cells_) : cell_at(split(t + 1));
  }

  // Calls fn(begin, end) for the 3^(D-1) contiguous index ranges covering the 3^D cells around
  // cell c. c must be an interior cell (any cell holding an active particle is).
  template <class Fn>
  void for_each_neighbour_range(std::size_t c, Fn&& fn) const {
    if (n_ghost_ == 0) {
      for_each_neighbour_row(c, [&](std::size_t row) { fn(start_[row - 1], start_[row + 2]); });
    } else {
      for_each_neighbour_row(c, [&](std::size_t row) {
        fn(start_[row - 1], start_[row + 2]);
        fn(ghost_base_ + ghost_start(row - 1), ghost_base_ + ghost_start(row + 2));
      });
    }
  }
  // The images stored before cell c's (ghost_start_'s window; see there).
  std::uint32_t ghost_start(std::size_t c) const {
    if (c <= ghost_lo_) return 0u;
    if (c > ghost_hi_) return static_cast<std::uint32_t>(n_ghost_);
    return ghost_start_[c - ghost_lo_];
  }
  // At most this many ranges per cell (real particles, then images, per x-row).
  static constexpr int kMaxRanges = 2 * (D == 3 ? 9 : (D == 2 ? 3 : 1));

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
  // Wraps every particle that crossed a periodic face back by one period (and a moving wall's
  // reference position with it).
  void wrap(ParticleSet<D>& ps) const {
    const long n = static_cast<long>(ps.size());
    const bool has_ref = !ps.pos_ref.empty();
#pragma omp parallel for schedule(static) if (n > ParticleSet <D>::kParallelMin)
    for (long i = 0; i < n; ++i) {
      for (int d = 0; d < D; ++d) {
        if (!periodic_[d]) continue;
        const double L = max_[d] - min_[d];
        const double x = ps.pos[i][d];
        double s = 0.0;
        if (x >= max_[d])
          s = -L;
        else if (x < min_[d])
          s = L;
        if (s == 0.0) continue;  // also NaN: left for the sort to exclude
        ps.pos[i][d] += s;
        // A moving wall is placed from its reference each substep: the reference goes with it
        // (a translation only; case setup refuses rotating bodies that cross a periodic face).
        if (has_ref && ps.role[i] == Role::MovingWall) ps.pos_ref[i][d] += s;
      }
    }
  }

  // Cell of an image (it may lie up to one cell outside the domain, in the padding).
  std::uint32_t ghost_cell_index(const Vec<D>& x) const {
    std::size_t c = 0, stride = 1;
    for (int d = 0; d < D; ++d) {
      long i = static_cast<long>(std::floor((x[d] - min_[d]) * inv_cell_)) + 1;
      i = std::clamp(i, 0L, n_[d] - 1);
      c += static_cast<std::size_t>(i) * stride;
      stride *= static_cast<std::size_t>(n_[d]);
    }
    return static_cast<std::uint32_t>(c);
  }

  // Appends the periodic images of the active particles, ordered by cell, and counts them
  // into ghost_start_. Serial O(N) scan; allocation-free once the buffers reached their size.
  void build_ghosts(ParticleSet<D>& ps) {
    collect_images(ps, -1);
    n_local_images_ = cand_src_.size();
    store_images(ps, nullptr);
    ps.n_ghost = n_ghost_;
    for (std::size_t k = 0; k < n_ghost_; ++k)
      has_fluid_[ghost_cell_[k]] |= ps.role[ghost_base_ + k] == Role::Fluid;
  }

  // The periodic images of the active particles as candidates (source, shift, cell), on every
  // periodic axis but `skip_axis`.
  void collect_images(const ParticleSet<D>& ps, int skip_axis) {
    const std::size_t n = ps.size();
    cand_src_.clear();
    cand_shift_.clear();
    cand_cell_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<D>& x = ps.pos[i];
      std::array<double, D> s{};
      const int axes = image_shifts(x, skip_axis, s);
      // One image per non-empty subset of the axes the particle is near (faces, edges, corners).
      for (int mask = axes; mask > 0; mask = (mask - 1) & axes) {
        Vec<D> shift = Vec<D>::Zero();
        for (int d = 0; d < D; ++d)
          if (mask & (1 << d)) shift[d] = s[d];
        cand_src_.push_back(static_cast<std::uint32_t>(i));
        cand_shift_.push_back(shift);
        cand_cell_.push_back(ghost_cell_index(x + shift));
      }
    }
  }

  // Orders the candidates by cell (stable: candidate order within a cell) into the image
  // block after the stored particles, grows every field by their number and stores the local
  // ones (source's record, shifted position). slot_of: each remote candidate's slot, in order.
  void store_images(ParticleSet<D>& ps, std::vector<std::uint32_t>* slot_of) {
    const std::size_t base = ps.pos.size(), ng = cand_src_.size();
    // The window of cells that hold images (a band along a slab face or a periodic face): the
    // counts over it only, not over the whole grid.
    std::uint32_t cmin = 0, cmax = 0;
    if (ng > 0) {
      const auto mm = std::minmax_element(cand_cell_.begin(), cand_cell_.end());
      cmin = *mm.first, cmax = *mm.second;
    }
    ghost_lo_ = cmin;
    ghost_hi_ = ng > 0 ? cmax + 1 : cmin;
    ghost_start_.assign(ghost_hi_ - ghost_lo_ + 1, 0u);
    for (std::size_t k = 0; k < ng; ++k) ++ghost_start_[cand_cell_[k] - cmin + 1];
    for (std::size_t c = 0; c + 1 < ghost_start_.size(); ++c)
      ghost_start_[c + 1] += ghost_start_[c];
    ghost_src_.resize(ng);
    ghost_shift_.resize(ng);
    ghost_cell_.resize(ng);
    if (slot_of) slot_of->resize(ng - n_local_images_);
    cursor_.assign(ghost_start_.begin(), ghost_start_.end());
    for (std::size_t k = 0; k < ng; ++k) {
      const std::uint32_t slot = cursor_[cand_cell_[k] - cmin]++;
      ghost_src_[slot] = cand_src_[k];
      ghost_shift_[slot] = cand_shift_[k];
      ghost_cell_[slot] = cand_cell_[k];
      if (k >= n_local_images_) (*slot_of)[k - n_local_images_] = slot;
    }
    ps.for_each_field([&](const FieldInfo& f, auto& a) {
      if (!ps.enabled(f)) return;
      a.resize(base + ng);
      if (n_local_images_ == 0) return;
      for (std::size_t k = 0; k < ng; ++k)
        if (ghost_src_[k] != kRemote) a[base + k] = a[ghost_src_[k]];
    });
    if (n_local_images_ > 0)
      for (std::size_t k = 0; k < ng; ++k)
        if (ghost_src_[k] != kRemote) ps.pos[base + k] += ghost_shift_[k];
    ghost_base_ = static_cast<std::uint32_t>(base);
    n_ghost_ = ng;
  }

  Vec<D> min_ = Vec<D>::Zero(), max_ = Vec<D>::Zero();
  double cell_size_ = 1.0, inv_cell_ = 1.0;
  std::array<long, D> n_{};
  std::size_t num_cells_ = 0;
  std::vector<std::uint32_t> start_, cursor_, order_, cell_of_;
  // sort(): each thread's histogram and cursors over its cells [first, last] (count_range_),
  // stored from index 0 for cell `first`.
  std::vector<std::vector<std::uint32_t>> counts_, cursors_;
  std::vector<std::array<std::uint32_t, 2>> count_range_;
  std::vector<std::uint8_t> has_fluid_;
  // Periodic axes and images.
  std::array<bool, D> periodic_{};
  bool any_periodic_ = false, by_exchange_ = false;
  std::size_t n_local_images_ = 0;  // images whose source is on this rank (periodic)
  std::size_t n_ghost_ = 0;
  std::uint32_t ghost_base_ = 0;
  // ghost_start(c) = the images in cells before c: ghost_start_[c - ghost_lo_] over the window
  // [ghost_lo_, ghost_hi_], none before it, all of them after it.
  std::vector<std::uint32_t> ghost_start_, ghost_src_, ghost_cell_, cand_src_, cand_cell_;
  std::size_t ghost_lo_ = 0, ghost_hi_ = 0;
  std::vector<Vec<D>> ghost_shift_, cand_shift_;
};

}  // namespace swell
