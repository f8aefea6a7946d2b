// Domain decomposition by slabs (issue #16): the global domain is cut along one axis (the
// longest, by default) into one slab per rank; a particle belongs to the rank whose slab holds
// its coordinate on that axis. Bounds are balanced by particle count from a global histogram
// (rebalance at an interval: a moving front unbalances a static split), never narrower than
// a minimum width (the kernel support, so a halo only ever comes from the next slab).
//
// Particles travel between ranks as whole records packed from the field table (every enabled
// field, raw bytes: the state arrives bit for bit). Migration sends the active particles that
// left this rank's slab to their owners; excluded particles stay where they were excluded.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "parallel/comm.hpp"
#include "solver/state/particle_set.hpp"

namespace swell::parallel {

// Bytes of one particle's record: the sum of its enabled fields' element sizes.
template <int D>
std::size_t record_bytes(const ParticleSet<D>& ps) {
  std::size_t b = 0;
  ps.for_each_field([&](const FieldInfo& f, const auto& a) {
    if (ps.enabled(f)) b += sizeof(typename std::decay_t<decltype(a)>::value_type);
  });
  return b;
}

// Writes particle i's record at out (record_bytes(ps) bytes).
template <int D>
void pack(const ParticleSet<D>& ps, std::size_t i, std::byte* out) {
  ps.for_each_field([&](const FieldInfo& f, const auto& a) {
    if (!ps.enabled(f)) return;
    using T = typename std::decay_t<decltype(a)>::value_type;
    std::memcpy(out, &a[i], sizeof(T));
    out += sizeof(T);
  });
}

// Overwrites particle i with the record at in (the same enabled fields).
template <int D>
void unpack(ParticleSet<D>& ps, std::size_t i, const std::byte* in) {
  ps.for_each_field([&](const FieldInfo& f, auto& a) {
    if (!ps.enabled(f)) return;
    using T = typename std::decay_t<decltype(a)>::value_type;
    std::memcpy(static_cast<void*>(&a[i]), in, sizeof(T));
    in += sizeof(T);
  });
}

// The slab bounds: rank r owns lo[r] <= x[axis] < lo[r + 1]; the first and last slabs reach
// to -inf / +inf along the axis (particles beyond the global domain are excluded by the
// sort, wherever they are).
struct Slabs {
  int axis = 0;
  std::vector<double> lo;  // size() + 1 entries; lo.front() and lo.back() are the domain's ends
  int size() const { return static_cast<int>(lo.size()) - 1; }
  int owner(double x) const {
    // The first bound above x, among the inner bounds lo[1..size-1].
    const auto it = std::upper_bound(lo.begin() + 1, lo.end() - 1, x);
    return static_cast<int>(it - (lo.begin() + 1));
  }
};

// Even slabs over [lo, hi] along axis for n ranks.
inline Slabs even_slabs(int axis, double lo, double hi, int n) {
  Slabs s;
  s.axis = axis;
  s.lo.resize(static_cast<std::size_t>(n) + 1);
  for (int r = 0; r <= n; ++r) s.lo[static_cast<std::size_t>(r)] = lo + (hi - lo) * r / n;
  return s;
}

// The longest axis of a box (the slab axis by default: the fewest particles per face).
template <int D>
int longest_axis(const Vec<D>& lo, const Vec<D>& hi) {
  int a = 0;
  for (int d = 1; d < D; ++d)
    if (hi[d] - lo[d] > hi[a] - lo[a]) a = d;
  return a;
}

// Bounds that split the active particles of every rank into equal counts along axis, from a
// global histogram of `bins` bins over [lo, hi] (resolution (hi - lo) / bins). Each slab is at
// least min_width wide (the kernel support); throws if the domain cannot hold size() such
// slabs. Collective: every rank calls it with the same arguments and gets the same bounds.
// `count` > 0: that many slabs instead of one per rank (e.g. from the whole set on every rank
// with Comm::self(), at the start of a run). `fluid_only`: count the fluid particles only (a
// step's work is mostly in the fluid's pair terms; DBC walls see fluid only and dry wall cells
// are skipped, so a slab of walls costs little); with no fluid, all particles. `weight` (one
// per active particle, e.g. pair_work's estimate): split the summed weights instead of counts.
template <int D>
Slabs balanced_slabs(const ParticleSet<D>& ps, int axis, double lo, double hi, double min_width,
                     const Comm& comm, int bins = 4096, int count = 0, bool fluid_only = false,
                     const std::vector<std::uint32_t>* weight = nullptr) {
  const int n = count > 0 ? count : comm.size();
  if (!(hi - lo >= n * min_width))
    throw std::invalid_argument(
        "domain decomposition: " + std::to_string(n) + " slabs of at least " +
        std::to_string(min_width) + " m (one kernel support) do not fit the domain's " +
        std::to_string(hi - lo) + " m along " + std::string(1, "xyz"[axis]) + "; use fewer ranks");
  std::vector<std::uint64_t> hist(static_cast<std::size_t>(bins), 0);
  const double w = (hi - lo) / bins;
  if (weight && weight->size() != ps.size())
    throw std::logic_error("balanced_slabs: one weight per active particle");
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double x = ps.pos[i][axis];
    if (!std::isfinite(x) || (!weight && fluid_only && !is_fluid(ps.role[i]))) continue;
    const int b = std::clamp(static_cast<int>((x - lo) / w), 0, bins - 1);
    hist[static_cast<std::size_t>(b)] += weight ? (*weight)[i] : 1u;
  }
  comm.sum_in_place(hist);
  std::uint64_t total = 0;
  for (auto c : hist) total += c;
  if (total == 0 && (fluid_only || weight))  // no work anywhere: fall back to counts
    return balanced_slabs(ps, axis, lo, hi, min_width, comm, bins, count, weight && fluid_only);
  Slabs s = even_slabs(axis, lo, hi, n);
  if (total == 0 || n == 1) return s;
  // Cut r at the first bin edge where the running count reaches r N / n, then push the cuts
  // apart to the minimum width (left to right, then right to left from the far end).
  std::uint64_t run = 0;
  int r = 1;
  for (int b = 0; b < bins && r < n; ++b) {
    run += hist[static_cast<std::size_t>(b)];
    while (r < n && run * static_cast<std::uint64_t>(n) >= total * static_cast<std::uint64_t>(r))
      s.lo[static_cast<std::size_t>(r++)] = lo + (b + 1) * w;
  }
  for (int k = 1; k < n; ++k)
    s.lo[static_cast<std::size_t>(k)] = std::max(s.lo[static_cast<std::size_t>(k)],
                                                 s.lo[static_cast<std::size_t>(k - 1)] + min_width);
  for (int k = n - 1; k >= 1; --k)
    s.lo[static_cast<std::size_t>(k)] = std::min(s.lo[static_cast<std::size_t>(k)],
                                                 s.lo[static_cast<std::size_t>(k + 1)] - min_width);
  return s;
}

// An estimate of each active particle's share of a step's work, for balanced_slabs, in the
// units of one candidate test. A particle in a cell with fluid in the 3^D cells around it
// (neighbours/pair_driver.hpp skips the others) tests every particle of those cells for the
// kernel support (N_all tests), then evaluates the pair terms of the neighbours it sees: every
// role for a fluid particle, fluid only for a wall one (DBC, mDBC); a neighbour is about a
// sixth of the candidates in 3D (sphere over 27 cells) and a third in 2D, and its terms cost
// about six candidate tests (16-lane float: the staging and the terms against the AVX-512
// distance test of 8 doubles), so the terms weigh about N_seen in 3D and 2 N_seen in 2D:
// weight = N_all + (4 - D) N_seen. Counted on a grid of the kernel support over the domain
// [dmin, dmax] (the cell grid's layout: a layer of padding cells on every side), from this
// rank's particles (halo images are dropped when it runs, so a particle near a slab face misses
// the other side's part, alike on both sides). `count_all`/`count_fluid`: per-cell scratch kept
// by the caller. Particles outside the domain weigh nothing.
template <int D>
void pair_work(const ParticleSet<D>& ps, const Vec<D>& dmin, const Vec<D>& dmax, double cell,
               std::vector<std::uint32_t>& count_all, std::vector<std::uint32_t>& count_fluid,
               std::vector<std::uint32_t>& weight) {
  std::array<long, D> n{};
  std::array<long, D> stride{};
  long cells = 1;
  for (int d = 0; d < D; ++d) {
    n[d] = static_cast<long>(std::floor((dmax[d] - dmin[d]) / cell)) + 3;
    stride[d] = cells;
    cells *= n[d];
  }
  count_all.assign(static_cast<std::size_t>(cells), 0u);
  count_fluid.assign(static_cast<std::size_t>(cells), 0u);
  const std::size_t np = ps.size();
  weight.assign(np, 0u);
  const auto cell_of = [&](const Vec<D>& x) -> long {
    long c = 0;
    for (int d = 0; d < D; ++d) {
      if (!(x[d] >= dmin[d] && x[d] <= dmax[d])) return -1;
      c += (static_cast<long>((x[d] - dmin[d]) / cell) + 1) * stride[d];
    }
    return c;
  };
  for (std::size_t i = 0; i < np; ++i) {
    const long c = cell_of(ps.pos[i]);
    if (c < 0) continue;
    ++count_all[static_cast<std::size_t>(c)];
    if (is_fluid(ps.role[i])) ++count_fluid[static_cast<std::size_t>(c)];
  }
  // The 3^D neighbour offsets (a cell inside the domain has all of them in the grid).
  std::array<long, 27> off{};
  int noff = 0;
  for (int k = 0; k < (D == 2 ? 9 : 27); ++k) {
    long o = 0;
    for (int d = 0, q = k; d < D; ++d, q /= 3) o += (q % 3 - 1) * stride[d];
    off[static_cast<std::size_t>(noff++)] = o;
  }
  for (std::size_t i = 0; i < np; ++i) {
    const long c = cell_of(ps.pos[i]);
    if (c < 0) continue;
    std::uint32_t all = 0, fluid = 0;
    for (int k = 0; k < noff; ++k) {
      const auto cc = static_cast<std::size_t>(c + off[static_cast<std::size_t>(k)]);
      all += count_all[cc];
      fluid += count_fluid[cc];
    }
    if (fluid == 0) continue;  // a dry cell: skipped by the pair loop
    weight[i] = all + static_cast<std::uint32_t>(4 - D) * (is_fluid(ps.role[i]) ? all : fluid);
  }
}

// Largest rank's active particle count over the mean (1 = perfect balance).
template <int D>
double imbalance(const ParticleSet<D>& ps, const Comm& comm) {
  const auto counts = comm.gather_all(ps.size());
  std::uint64_t mx = 0, sum = 0;
  for (auto c : counts) mx = std::max(mx, c), sum += c;
  return sum ? static_cast<double>(mx) * comm.size() / static_cast<double>(sum) : 1.0;
}

// Sends every active particle that lies outside this rank's slab to its owner and takes in
// those that arrive (in sender-rank order, each sender's in its own order) into the leaving
// ones' slots, then after the active range (before the excluded particles); slots left empty
// take the last staying particles. Only particles that move are copied, and the layout follows
// from the data alone, so the result is deterministic for a fixed rank count. Periodic images must
// have been dropped. The buffers are the caller's and are reused (no allocation once grown).
// `neighbours_first`: when no particle on any rank goes further than the next slab (one
// allreduce tells), the records travel point to point to the two neighbours
// (Comm::neighbour_exchange, latency independent of the rank count) instead of by an
// all-to-all; the result is the same, arrivals in the same order.
struct MigrationBuffers {
  std::vector<std::byte> send, recv;
  std::vector<int> send_count, recv_count, recv_displ;
  std::vector<int> dest;               // per leaving particle: its owner
  std::vector<std::uint32_t> order;    // the leaving particles, then the arrivals' slots
  std::vector<std::size_t> cursor;     // packing offsets per destination rank
  std::size_t sent = 0, received = 0;  // particles, this call
};

// `ring`: the slab axis is periodic (the particles wrapped before this call), so the first and
// the last rank are neighbours too.
template <int D>
void migrate(ParticleSet<D>& ps, const Slabs& slabs, const Comm& comm, MigrationBuffers& buf,
             bool neighbours_first = false, bool ring = false) {
  if (ps.n_ghost != 0) throw std::logic_error("migrate: drop the periodic images first");
  const int me = comm.rank(), n = comm.size();
  if (slabs.size() != n) throw std::invalid_argument("migrate: one slab per rank");
  const int below = ring ? (me + n - 1) % n : me - 1, above = ring ? (me + 1) % n : me + 1;
  const std::size_t rec = record_bytes(ps), na = ps.size(), total = ps.total();
  buf.send_count.assign(static_cast<std::size_t>(n), 0);
  // The leaving particles (ascending) and their owners. Own slab [lo, hi); the first and the
  // last slab reach on to -inf and +inf (Slabs::owner). A non-finite position stays here: the
  // sort excludes it.
  buf.order.clear();
  buf.dest.clear();
  const double own_lo = me > 0 ? slabs.lo[static_cast<std::size_t>(me)]
                               : -std::numeric_limits<double>::infinity(),
               own_hi = me + 1 < n ? slabs.lo[static_cast<std::size_t>(me) + 1]
                                   : std::numeric_limits<double>::infinity();
  bool far = false;
  for (std::size_t i = 0; i < na; ++i) {
    const double x = ps.pos[i][slabs.axis];
    if ((x >= own_lo && x < own_hi) || !std::isfinite(x)) continue;
    const int o = slabs.owner(x);
    buf.order.push_back(static_cast<std::uint32_t>(i));
    buf.dest.push_back(o);
    buf.send_count[static_cast<std::size_t>(o)] += static_cast<int>(rec);
    far = far || (o != below && o != above);
  }
  const std::size_t leaving = buf.order.size();
  const bool neighbours = neighbours_first && n > 1 && comm.max(far ? 1.0 : 0.0) == 0.0;
  // Pack in destination-rank order.
  if (buf.send.size() < leaving * rec) buf.send.resize(leaving * rec);
  {
    std::vector<std::size_t>& cursor = buf.cursor;
    cursor.assign(static_cast<std::size_t>(n), 0);
    std::size_t off = 0;
    for (int r = 0; r < n; ++r) {
      cursor[static_cast<std::size_t>(r)] = off;
      off += static_cast<std::size_t>(buf.send_count[static_cast<std::size_t>(r)]);
    }
    for (std::size_t k = 0; k < leaving; ++k) {
      auto& c = cursor[static_cast<std::size_t>(buf.dest[k])];
      pack(ps, buf.order[k], buf.send.data() + c);
      c += rec;
    }
  }
  if (neighbours) {
    // The send buffer is in rank order: each neighbour's part starts where the lower ranks'
    // parts end. On a ring of 2 ranks both neighbours are the other rank: its whole part goes
    // as the message to `below`, an empty one to `above`.
    const auto part = [&](int r) {
      std::size_t off = 0;
      for (int q = 0; q < r; ++q) off += static_cast<std::size_t>(buf.send_count[q]);
      return off;
    };
    const bool same = below == above;
    const std::size_t lo = below >= 0 ? static_cast<std::size_t>(buf.send_count[below]) : 0,
                      hi = above < n && !same ? static_cast<std::size_t>(buf.send_count[above]) : 0;
    std::size_t from_lo = 0;
    comm.neighbour_exchange(buf.send.data() + (below >= 0 ? part(below) : 0), lo,
                            buf.send.data() + (above < n ? part(above) : 0), hi, buf.recv, from_lo,
                            ring);
    buf.recv_count.assign(static_cast<std::size_t>(n), 0);
    buf.recv_displ.assign(static_cast<std::size_t>(n), 0);
    if (same) {
      buf.recv_count[below] = static_cast<int>(buf.recv.size());
    } else {
      if (below >= 0) buf.recv_count[below] = static_cast<int>(from_lo);
      if (above < n) {
        buf.recv_count[above] = static_cast<int>(buf.recv.size() - from_lo);
        buf.recv_displ[above] = static_cast<int>(from_lo);
      }
    }
  } else {
    comm.alltoallv(buf.send, buf.send_count, buf.recv, buf.recv_count, buf.recv_displ);
  }
  std::size_t arriving = 0;
  for (int r = 0; r < n; ++r) {
    const auto bytes = static_cast<std::size_t>(buf.recv_count[static_cast<std::size_t>(r)]);
    if (bytes % rec != 0)
      throw std::runtime_error("migrate: rank " + std::to_string(r) +
                               " sent records of another size (its optional fields differ)");
    arriving += bytes / rec;
  }
  // New layout, copying only the particles that move (a permutation of the whole set here
  // cost as much as the sort that follows): the arrivals (rank order, then as sent) take the
  // leaving particles' slots in index order, then go after the active particles; leaving slots
  // left over take the last staying particles; the excluded particles stay last. The order is
  // fixed by the data, so a run on a given number of ranks stays deterministic.
  if (leaving > 0 || arriving > 0) {
    std::vector<std::uint32_t>& holes = buf.order;  // the leaving particles, ascending
    const std::size_t excluded = total - na, active = na - leaving + arriving;
    const auto move_particle = [&](std::size_t from, std::size_t to) {
      ps.for_each_field([&](const FieldInfo& f, auto& a) {
        if (ps.enabled(f)) a[to] = a[from];
      });
    };
    if (arriving > leaving) {  // grow, the excluded block moving back behind the arrivals
      ps.for_each_field([&](const FieldInfo& f, auto& a) {
        if (!ps.enabled(f)) return;
        a.resize(active + excluded);
        std::move_backward(a.begin() + static_cast<long>(na), a.begin() + static_cast<long>(total),
                           a.begin() + static_cast<long>(active + excluded));
      });
      for (std::size_t i = na; i < active; ++i) holes.push_back(static_cast<std::uint32_t>(i));
    } else if (leaving > arriving) {
      // Slots holes[arriving..] stay empty: fill each, lowest first, with the last particle
      // that stays (empty slots at the end are dropped as they are met). The slots the
      // arrivals take lie below every empty one, so none of them moves.
      std::size_t end = na, back = leaving;  // empty slots not yet handled: holes[k..back)
      for (std::size_t k = arriving; k < back; ++k) {
        while (back > k && holes[back - 1] + 1 == end) --back, --end;
        if (k == back) break;
        move_particle(end - 1, holes[k]);
        --end;
      }
      if (end != active) throw std::logic_error("migrate: the compaction lost count");
      ps.for_each_field([&](const FieldInfo& f, auto& a) {
        if (!ps.enabled(f)) return;
        std::move(a.begin() + static_cast<long>(na), a.begin() + static_cast<long>(total),
                  a.begin() + static_cast<long>(active));
        a.resize(active + excluded);
      });
    }
    std::size_t slot = 0;
    for (int r = 0; r < n; ++r) {
      const std::size_t k =
          static_cast<std::size_t>(buf.recv_count[static_cast<std::size_t>(r)]) / rec;
      const std::byte* in = buf.recv.data() + buf.recv_displ[static_cast<std::size_t>(r)];
      for (std::size_t j = 0; j < k; ++j, ++slot, in += rec) unpack(ps, holes[slot], in);
    }
    ps.n_active = active;
  }
  buf.sent = leaving;
  buf.received = arriving;
}

// Sends every active particle of `ps` to the rank whose slab holds it: a set-up distributed
// over the ranks, or a checkpoint read in blocks of rows (run/run.cpp). The records
// travel in rounds of at most `chunk` bytes received per rank (MPI counts and offsets are
// ints); the staying
// particles are compacted in place (no scratch the size of the set) and the arrivals appended,
// the excluded particles (kept for the record) staying last. With `keys` (one per active
// particle; e.g. the row it came from) the keys travel along and the active particles end
// sorted by them (`keys` too); otherwise staying ones come first, then arrivals by sender. The
// extra memory is that of the particles that move. There must be no images. Returns how many
// left this rank.
template <int D>
std::size_t redistribute(ParticleSet<D>& ps, const Slabs& slabs, const Comm& comm,
                         std::vector<std::uint64_t>* keys = nullptr,
                         std::size_t chunk = std::size_t{256} << 20) {
  if (ps.n_ghost != 0) throw std::logic_error("redistribute: drop the images first");
  const int me = comm.rank(), n = comm.size();
  const std::size_t rec = record_bytes(ps), n0 = ps.size(), total = ps.total();
  const std::size_t krec = keys ? sizeof(std::uint64_t) : 0, full = rec + krec;
  if (keys && keys->size() != n0) throw std::invalid_argument("redistribute: one key per particle");
  std::vector<int> dest(n0);
  std::vector<std::uint32_t> leaving;
  for (std::size_t i = 0; i < n0; ++i) {
    const double x = ps.pos[i][slabs.axis];
    dest[i] = std::isfinite(x) ? slabs.owner(x) : 0;  // as share_by_slabs: rank 0 excludes it
    if (dest[i] != me) leaving.push_back(static_cast<std::uint32_t>(i));
  }
  // A rank receives at most n senders' rounds: `chunk` in all (MPI's int offsets).
  const std::size_t per_round =
      std::max<std::size_t>(1, chunk / (full * static_cast<std::size_t>(n)));
  const auto rounds = static_cast<long>(
      comm.max(static_cast<double>((leaving.size() + per_round - 1) / per_round)));
  std::vector<std::byte> send, recv, arrived;
  std::vector<int> send_count, recv_count, recv_displ;
  std::vector<std::size_t> cursor(static_cast<std::size_t>(n));
  for (long round = 0; round < rounds; ++round) {
    const std::size_t first = std::min(leaving.size(), static_cast<std::size_t>(round) * per_round);
    const std::size_t last = std::min(leaving.size(), first + per_round);
    send_count.assign(static_cast<std::size_t>(n), 0);
    for (std::size_t k = first; k < last; ++k)
      send_count[static_cast<std::size_t>(dest[leaving[k]])] += static_cast<int>(full);
    std::size_t off = 0;
    for (int r = 0; r < n; ++r) {
      cursor[static_cast<std::size_t>(r)] = off;
      off += static_cast<std::size_t>(send_count[static_cast<std::size_t>(r)]);
    }
    send.resize(off);
    for (std::size_t k = first; k < last; ++k) {
      auto& c = cursor[static_cast<std::size_t>(dest[leaving[k]])];
      pack(ps, leaving[k], send.data() + c);
      if (keys) std::memcpy(send.data() + c + rec, &(*keys)[leaving[k]], krec);
      c += full;
    }
    comm.alltoallv(send, send_count, recv, recv_count, recv_displ);
    for (int r = 0; r < n; ++r) {
      const auto bytes = static_cast<std::size_t>(recv_count[static_cast<std::size_t>(r)]);
      if (bytes % full != 0)
        throw std::runtime_error("redistribute: rank " + std::to_string(r) +
                                 " sent records of another size (its optional fields differ)");
      const std::byte* in = recv.data() + recv_displ[static_cast<std::size_t>(r)];
      arrived.insert(arrived.end(), in, in + bytes);
    }
  }
  std::vector<std::byte>().swap(send);
  std::vector<std::byte>().swap(recv);
  const std::size_t kept = n0 - leaving.size(), arriving = arrived.size() / full;
  const std::size_t excluded = total - n0;
  ps.for_each_field([&](const FieldInfo& f, auto& a) {
    if (!ps.enabled(f)) return;
    std::size_t w = 0;
    for (std::size_t i = 0; i < n0; ++i)
      if (dest[i] == me) a[w++] = a[i];
    for (std::size_t i = n0; i < total; ++i) a[w++] = a[i];  // the excluded block
    a.resize(kept + arriving + excluded);
    if (arriving > 0 && excluded > 0)
      std::move_backward(a.begin() + static_cast<long>(kept),
                         a.begin() + static_cast<long>(kept + excluded), a.end());
  });
  if (keys) {
    std::size_t w = 0;
    for (std::size_t i = 0; i < n0; ++i)
      if (dest[i] == me) (*keys)[w++] = (*keys)[i];
    keys->resize(kept + arriving);
  }
  for (std::size_t k = 0; k < arriving; ++k) {
    unpack(ps, kept + k, arrived.data() + k * full);
    if (keys) std::memcpy(&(*keys)[kept + k], arrived.data() + k * full + rec, krec);
  }
  ps.n_active = kept + arriving;
  if (keys) {
    std::vector<std::uint32_t> order(kept + arriving);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return (*keys)[a] < (*keys)[b]; });
    for (std::size_t i = kept + arriving; i < ps.total(); ++i)
      order.push_back(static_cast<std::uint32_t>(i));
    ps.permute_in_place(order);
    std::sort(keys->begin(), keys->end());
  }
  return leaving.size();
}

// An empty set with the same optional fields enabled as `like`.
template <int D>
ParticleSet<D> empty_like(const ParticleSet<D>& like) {
  ParticleSet<D> out;
  like.for_each_field([&](const FieldInfo& f, const auto&) {
    if (f.optional && like.enabled(f)) out.mark_enabled(f);
  });
  return out;
}

// The entries `index` of `all` (in that order), the first n_active of them active.
template <int D>
ParticleSet<D> subset(const ParticleSet<D>& all, const std::vector<std::uint32_t>& index,
                      std::size_t n_active) {
  ParticleSet<D> out = empty_like(all);
  const auto& src = all;
  out.for_each_field([&](const FieldInfo& f, auto& a) {
    if (!out.enabled(f)) return;
    src.for_each_field([&](const FieldInfo& g, const auto& b) {
      if constexpr (std::is_same_v<std::decay_t<decltype(a)>, std::decay_t<decltype(b)>>) {
        if (g.index != f.index) return;
        a.resize(index.size());
        for (std::size_t k = 0; k < index.size(); ++k) a[k] = b[index[k]];
      }
    });
  });
  out.n_active = n_active;
  return out;
}

// Rank `rank`'s share of a whole particle set at the start of a decomposed run (or a restart
// on another number of ranks): the active particles its slab owns, in their order; the
// excluded ones (kept for the record) all go to rank 0.
template <int D>
ParticleSet<D> share_by_slabs(const ParticleSet<D>& all, const Slabs& slabs, int rank) {
  std::vector<std::uint32_t> index;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const double x = all.pos[i][slabs.axis];
    // A non-finite position stays with rank 0, whose sort excludes it.
    if ((std::isfinite(x) ? slabs.owner(x) : 0) == rank)
      index.push_back(static_cast<std::uint32_t>(i));
  }
  const std::size_t active = index.size();
  if (rank == 0)
    for (std::size_t i = all.size(); i < all.total(); ++i)
      index.push_back(static_cast<std::uint32_t>(i));
  return subset(all, index, active);
}

// Where each rank's particles are in a gathered set (gather_to_root): active blocks in rank
// order, then excluded blocks in rank order.
struct GatherLayout {
  std::vector<std::uint64_t> active, excluded;  // per rank
};

// Rank `rank`'s share by a gathered layout: exactly the particles it held, in its order (a
// restart on the same number of ranks continues bit for bit).
template <int D>
ParticleSet<D> share_by_layout(const ParticleSet<D>& all, const GatherLayout& layout, int rank) {
  std::uint64_t a0 = 0, e0 = 0, na = 0, ne = 0;
  for (std::size_t r = 0; r < layout.active.size(); ++r) {
    if (static_cast<int>(r) < rank) a0 += layout.active[r], e0 += layout.excluded[r];
    na += layout.active[r], ne += layout.excluded[r];
  }
  if (na != all.size() || na + ne != all.total())
    throw std::invalid_argument("share_by_layout: the layout does not match the particles");
  const auto r = static_cast<std::size_t>(rank);
  std::vector<std::uint32_t> index;
  for (std::uint64_t k = 0; k < layout.active[r]; ++k)
    index.push_back(static_cast<std::uint32_t>(a0 + k));
  for (std::uint64_t k = 0; k < layout.excluded[r]; ++k)
    index.push_back(static_cast<std::uint32_t>(na + e0 + k));
  return subset(all, index, static_cast<std::size_t>(layout.active[r]));
}

// Every rank's particles (active and excluded) on rank 0, with the per-particle vectors
// `extra` (e.g. accelerations, one per active particle; empty: none) gathered alongside into
// extra_out. Collective; out and extra_out are filled on rank 0 only (other ranks: untouched).
struct GatherBuffers {
  std::vector<std::byte> send, recv;
  std::vector<int> send_count, recv_count, recv_displ;
  GatherLayout layout;  // the last gather's (gather_to_root returns it)
};

template <int D>
const GatherLayout& gather_to_root(const ParticleSet<D>& ps, const Comm& comm, ParticleSet<D>& out,
                                   const std::vector<Vec<D>>* extra, std::vector<Vec<D>>* extra_out,
                                   GatherBuffers& buf) {
  const std::size_t rec = record_bytes(ps), xrec = extra ? sizeof(Vec<D>) : 0;
  GatherLayout& layout = buf.layout;  // reused: no allocation per gather once sized
  comm.gather_all(ps.size(), layout.active);
  comm.gather_all(ps.total() - ps.size(), layout.excluded);
  const auto n = static_cast<std::size_t>(comm.size());
  // Two rounds: the active particles (with their extra values), then the excluded ones.
  for (int round = 0; round < 2; ++round) {
    const std::size_t first = round == 0 ? 0 : ps.size(),
                      last = round == 0 ? ps.size() : ps.total();
    const std::size_t r = round == 0 ? rec + xrec : rec;
    buf.send.resize((last - first) * r);
    std::byte* o = buf.send.data();
    for (std::size_t i = first; i < last; ++i, o += r) {
      pack(ps, i, o);
      if (round == 0 && extra) std::memcpy(o + rec, (*extra)[i].data(), sizeof(Vec<D>));
    }
    buf.send_count.assign(n, 0);
    buf.send_count[0] = static_cast<int>((last - first) * r);
    comm.alltoallv(buf.send, buf.send_count, buf.recv, buf.recv_count, buf.recv_displ);
    if (comm.rank() != 0) continue;
    std::uint64_t count = 0;
    for (std::size_t k = 0; k < n; ++k) count += round == 0 ? layout.active[k] : layout.excluded[k];
    if (round == 0) {
      // Rebuilt only when empty: later gathers reuse the arrays (no allocation once grown).
      if (out.pos.empty()) out = empty_like(ps);
      out.n_ghost = 0;
      out.for_each_field([&](const FieldInfo& f, auto& a) {
        if (out.enabled(f)) a.resize(count);
      });
      if (extra_out) extra_out->resize(count);
      for (std::uint64_t k = 0; k < count; ++k) {
        const std::byte* in = buf.recv.data() + k * r;
        unpack(out, k, in);
        if (extra_out && extra) std::memcpy((*extra_out)[k].data(), in + rec, sizeof(Vec<D>));
      }
      out.n_active = count;
    } else {
      const std::size_t base = out.pos.size();
      out.for_each_field([&](const FieldInfo& f, auto& a) {
        if (out.enabled(f)) a.resize(base + count);
      });
      for (std::uint64_t k = 0; k < count; ++k) unpack(out, base + k, buf.recv.data() + k * r);
    }
  }
  return layout;
}

// The active particles `select` (indices into ps, increasing) of every rank on rank 0, in
// rank order and each rank's order, with `extra` (one per active particle) alongside: a
// filtered gather_to_root (the same relative order). Collective; `out` holds only active
// particles. The counts per rank go to `counts` (rank 0). No allocation once the buffers grew.
template <int D>
void gather_selected_to_root(const ParticleSet<D>& ps, const std::vector<std::uint32_t>& select,
                             const Comm& comm, ParticleSet<D>& out,
                             const std::vector<Vec<D>>& extra, std::vector<Vec<D>>& extra_out,
                             GatherBuffers& buf, std::vector<std::uint64_t>& counts) {
  const std::size_t rec = record_bytes(ps), r = rec + sizeof(Vec<D>);
  const auto n = static_cast<std::size_t>(comm.size());
  comm.gather_all(select.size(), counts);
  buf.send.resize(select.size() * r);
  std::byte* o = buf.send.data();
  for (const std::uint32_t i : select) {
    pack(ps, i, o);
    std::memcpy(o + rec, extra[i].data(), sizeof(Vec<D>));
    o += r;
  }
  buf.send_count.assign(n, 0);
  buf.send_count[0] = static_cast<int>(select.size() * r);
  comm.alltoallv(buf.send, buf.send_count, buf.recv, buf.recv_count, buf.recv_displ);
  if (comm.rank() != 0) return;
  std::uint64_t count = 0;
  for (auto c : counts) count += c;
  if (out.pos.empty()) out = empty_like(ps);
  out.n_ghost = 0;
  out.for_each_field([&](const FieldInfo& f, auto& a) {
    if (out.enabled(f)) a.resize(count);
  });
  extra_out.resize(count);
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::byte* in = buf.recv.data() + k * r;
    unpack(out, k, in);
    std::memcpy(extra_out[k].data(), in + rec, sizeof(Vec<D>));
  }
  out.n_active = count;
}

}  // namespace swell::parallel
