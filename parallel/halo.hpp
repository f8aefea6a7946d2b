// The slab decomposition in the time loop (issue #16): SlabExchange is the Exchange
// (solver/time/exchange.hpp) of a run on several ranks.
//
// - migrate: every `rebalance_every` steps the slab bounds are balanced by the estimated work
//   of the pair loop (balanced_slabs weighted by pair_work: the neighbours each particle's pair
//   terms visit), then the particles that left this rank's slab go to their owners (migrate,
//   only the particles that move are copied).
// - build_halo (after the sort): the active particles within `width` of a slab face are sent,
//   whole records, to the rank on the other side, which stores them as images after its own
//   particles, placed in its cell grid (CellGrid::place_remote_images). `width` is the kernel
//   support plus whatever reach a stage adds beyond it (mDBC: the ghost node lies up to twice
//   the wall normal from its wall particle), and each slab is at least that wide, so a halo
//   only ever comes from the next slab.
// - refresh: position, velocity and density of the same particles again, into the same slots.
// - Periodic axes (configure): along the slab axis the slabs form a ring, the first rank
//   sending its particles within one cell (one kernel support) of the domain's low face to the
//   last rank shifted by +L, the last rank its high-face ones to the first shifted by -L (one
//   periodic image per particle, as on one rank); along the other periodic axes each particle
//   sent also goes as its periodic images (the same faces-edges-corners rule as
//   CellGrid::build_ghosts), and the receiver adds its own particles' images there
//   (CellGrid::place_remote_images). Each rank so holds the single-rank run's images near it.
// Halo builds, refreshes and migration talk to the two neighbouring ranks only (migration
// after a rebalance, or when a particle jumped further than one slab, uses an all-to-all). Every
// call is collective. The order of everything sent is fixed (rank order, then the local order), so
// a run on a given number of ranks is deterministic.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "parallel/comm.hpp"
#include "parallel/decomposition.hpp"
#include "solver/time/exchange.hpp"

namespace swell::parallel {

// What the exchange moved, for the run summary and the bench figures.
struct HaloStats {
  std::uint64_t builds = 0;       // halo builds (one per evaluation)
  std::uint64_t images = 0;       // images received, summed over the builds
  std::uint64_t image_bytes = 0;  // bytes received in builds and refreshes
  std::uint64_t migrated = 0;     // particles sent away by migration
  std::uint64_t rebalances = 0;
  double seconds = 0.0;  // in migrate, build_halo and refresh (communication included)
};

template <int D>
class SlabExchange final : public Exchange<D> {
 public:
  // slabs: the initial bounds (one slab per rank of comm, each at least `width` wide);
  // [lo, hi]: the global domain along the slab axis (rebalancing keeps within it).
  SlabExchange(Comm comm, Slabs slabs, double width, long rebalance_every)
      : comm_(comm), slabs_(std::move(slabs)), width_(width), rebalance_every_(rebalance_every) {
    if (slabs_.size() != comm_.size())
      throw std::invalid_argument("SlabExchange: one slab per rank");
    for (int r = 1; r + 1 < slabs_.size(); ++r)
      if (!(slabs_.lo[static_cast<std::size_t>(r) + 1] - slabs_.lo[static_cast<std::size_t>(r)] >=
            width_ * (1.0 - 1e-12)))
        throw std::invalid_argument("SlabExchange: slab " + std::to_string(r) +
                                    " is narrower than the halo width");
  }

  const Slabs& slabs() const { return slabs_; }
  const HaloStats& stats() const { return stats_; }
  double width() const { return width_; }
  // Images of the last halo build on this rank.
  std::size_t images() const { return slot_of_.size(); }

  void configure(const CellGrid<D>& grid) override {
    periodic_ = grid.any_periodic();
    dmin_ = grid.domain_min();
    dmax_ = grid.domain_max();
    cell_ = grid.cell_size();
    ring_ = grid.periodic(slabs_.axis);
  }

  void migrate(ParticleSet<D>& ps, long step) override {
    const double t0 = wtime();
    bool rebalanced = false;
    if (rebalance_every_ > 0 && step > 0 && step % rebalance_every_ == 0 &&
        step != last_rebalance_) {
      rebalanced = true;
      pair_work(ps, dmin_, dmax_, cell_, work_all_, work_fluid_, work_);
      slabs_ = balanced_slabs(ps, slabs_.axis, slabs_.lo.front(), slabs_.lo.back(), width_, comm_,
                              4096, 0, true, &work_);
      last_rebalance_ = step;
      ++stats_.rebalances;
    }
    // After a rebalance particles may go to any rank; otherwise only to a neighbour (a step
    // moves a particle far less than a slab's width), checked by migrate itself.
    parallel::migrate(ps, slabs_, comm_, mig_, !rebalanced, ring_);
    stats_.migrated += mig_.sent;
    stats_.seconds += wtime() - t0;
  }

  void build_halo(ParticleSet<D>& ps, CellGrid<D>& grid) override {
    const double t0 = wtime();
    const int me = comm_.rank(), n = comm_.size();
    const int ax = slabs_.axis;
    const double lo = slabs_.lo[static_cast<std::size_t>(me)],
                 hi = slabs_.lo[static_cast<std::size_t>(me) + 1];
    send_lo_.clear();
    send_hi_.clear();
    shift_lo_.clear();
    shift_hi_.clear();
    if (!periodic_) {
      for (std::size_t i = 0; i < ps.size(); ++i) {
        const double x = ps.pos[i][ax];
        if (me > 0 && x < lo + width_) send_lo_.push_back(static_cast<std::uint32_t>(i));
        if (me + 1 < n && x >= hi - width_) send_hi_.push_back(static_cast<std::uint32_t>(i));
      }
    } else {
      const double period = dmax_[ax] - dmin_[ax];
      for (std::size_t i = 0; i < ps.size(); ++i) {
        const double x = ps.pos[i][ax];
        const auto id = static_cast<std::uint32_t>(i);
        if (me > 0 && x < lo + width_) add_sends(grid, ps.pos[i], id, 0.0, send_lo_, shift_lo_);
        if (ring_ && me == 0 && x - dmin_[ax] < cell_)
          add_sends(grid, ps.pos[i], id, period, send_lo_, shift_lo_);
        if (me + 1 < n && x >= hi - width_)
          add_sends(grid, ps.pos[i], id, 0.0, send_hi_, shift_hi_);
        if (ring_ && me == n - 1 && dmax_[ax] - x < cell_)
          add_sends(grid, ps.pos[i], id, -period, send_hi_, shift_hi_);
      }
    }
    const std::size_t rec = record_bytes(ps);
    exchange_lists(ps, rec,
                   [&](const ParticleSet<D>& p, std::size_t i, const Vec<D>* s, std::byte* out) {
                     pack(p, i, out);
                     if (s) write_shifted(p.pos[i], *s, out);  // pos: the record's first field
                   });
    const std::size_t arriving = total_received(rec);
    // Positions first (pos is the field table's first field, at the start of each record).
    xs_.resize(arriving);
    for (std::size_t k = 0; k < arriving; ++k)
      std::memcpy(xs_[k].data(), recv_.data() + k * rec, sizeof(Vec<D>));
    const std::size_t base = ps.pos.size();
    // Grows the arrays by the remote images and this rank's own periodic images (stored).
    grid.place_remote_images(ps, xs_, slot_of_, ax);
    images_ = ps.pos.size() - base;
    for (std::size_t k = 0; k < arriving; ++k)
      unpack(ps, base + slot_of_[k], recv_.data() + k * rec);
    grid.attach_remote_images(ps);
    ++stats_.builds;
    stats_.images += arriving;
    stats_.image_bytes += arriving * rec;
    stats_.seconds += wtime() - t0;
  }

  void refresh(ParticleSet<D>& ps) override {
    const double t0 = wtime();
    // pos, vel, rho: what the pair terms read and the integrator changed (stored types).
    constexpr std::size_t xv = sizeof(Vec<D>), vv = sizeof(StateVec<D>), rv = sizeof(StateReal);
    constexpr std::size_t rec = xv + vv + rv;
    exchange_lists(ps, rec,
                   [](const ParticleSet<D>& p, std::size_t i, const Vec<D>* s, std::byte* out) {
                     if (s)
                       write_shifted(p.pos[i], *s, out);
                     else
                       std::memcpy(out, p.pos[i].data(), xv);
                     std::memcpy(out + xv, p.vel[i].data(), vv);
                     std::memcpy(out + xv + vv, &p.rho[i], rv);
                   });
    const std::size_t arriving = total_received(rec);
    if (arriving != slot_of_.size() || ps.n_ghost != images_)
      throw std::logic_error("SlabExchange::refresh: the halo changed since it was built");
    const std::size_t base = ps.ghost_begin();
    for (std::size_t k = 0; k < arriving; ++k) {
      const std::byte* in = recv_.data() + k * rec;
      const std::size_t j = base + slot_of_[k];
      std::memcpy(ps.pos[j].data(), in, xv);
      std::memcpy(ps.vel[j].data(), in + xv, vv);
      std::memcpy(&ps.rho[j], in + xv + vv, rv);
    }
    stats_.image_bytes += arriving * rec;
    stats_.seconds += wtime() - t0;
  }

  void refresh_vectors(std::vector<Vec<D>>& field, std::size_t ghost_begin) override {
    const double t0 = wtime();
    constexpr std::size_t rec = sizeof(Vec<D>);
    exchange_lists(field, rec,
                   [](const std::vector<Vec<D>>& f, std::size_t i, const Vec<D>*, std::byte* out) {
                     std::memcpy(out, f[i].data(), rec);
                   });
    const std::size_t arriving = total_received(rec);
    if (arriving != slot_of_.size() || field.size() < ghost_begin + images_)
      throw std::logic_error("SlabExchange::refresh_vectors: the halo changed since it was built");
    for (std::size_t k = 0; k < arriving; ++k)
      std::memcpy(field[ghost_begin + slot_of_[k]].data(), recv_.data() + k * rec, rec);
    stats_.image_bytes += arriving * rec;
    stats_.seconds += wtime() - t0;
  }

  double global_min(double x) const override { return comm_.min(x); }
  std::uint64_t global_sum(std::uint64_t x) const override { return comm_.sum(x); }
  double global_max(double x) const override { return comm_.max(x); }
  void global_sum_in_place(std::vector<double>& v) const override { comm_.sum_in_place(v); }
  int rank() const override { return comm_.rank(); }
  int ranks() const override { return comm_.size(); }

  // The slab bounds, so a restart on the same ranks continues with them.
  void save(std::map<std::string, double>& out) const override {
    out["decomposition.ranks"] = comm_.size();
    out["decomposition.axis"] = slabs_.axis;
    for (std::size_t r = 0; r < slabs_.lo.size(); ++r)
      out["decomposition.lo." + std::to_string(r)] = slabs_.lo[r];
  }

 private:
  static double wtime();

  // Sends send_lo_ to rank - 1 and send_hi_ to rank + 1 (a ring along a periodic slab axis),
  // `rec` bytes per particle written by write(ps, i, shift or nullptr, out); what arrives is in
  // recv_ (from rank - 1, then from rank + 1). Point to point with the two neighbours only
  // (Comm::neighbour_exchange).
  template <class Source, class Write>
  void exchange_lists(const Source& ps, std::size_t rec, Write&& write) {
    const std::size_t lo_bytes = send_lo_.size() * rec, hi_bytes = send_hi_.size() * rec;
    if (send_.size() < lo_bytes + hi_bytes) send_.resize(lo_bytes + hi_bytes);
    std::byte* out = send_.data();
    const bool shifted = periodic_;
    for (std::size_t k = 0; k < send_lo_.size(); ++k, out += rec)
      write(ps, send_lo_[k], shifted ? &shift_lo_[k] : nullptr, out);
    for (std::size_t k = 0; k < send_hi_.size(); ++k, out += rec)
      write(ps, send_hi_[k], shifted ? &shift_hi_[k] : nullptr, out);
    std::size_t recv_lo = 0;
    comm_.neighbour_exchange(send_.data(), lo_bytes, send_.data() + lo_bytes, hi_bytes, recv_,
                             recv_lo, ring_);
  }
  // Particle i sent with the shift `base` along the slab axis, and as its periodic images
  // along the other periodic axes (every non-empty subset of the faces it is within one cell
  // of, as CellGrid::collect_images).
  void add_sends(const CellGrid<D>& grid, const Vec<D>& x, std::uint32_t i, double base,
                 std::vector<std::uint32_t>& list, std::vector<Vec<D>>& shifts) const {
    const int ax = slabs_.axis;
    std::array<double, D> s{};
    const int axes = grid.image_shifts(x, ax, s);
    // The empty subset (mask 0) is the particle itself, shifted by `base` only.
    for (int mask = axes;; mask = (mask - 1) & axes) {
      Vec<D> shift = Vec<D>::Zero();
      shift[ax] = base;
      for (int d = 0; d < D; ++d)
        if (mask & (1 << d)) shift[d] = s[d];
      list.push_back(i);
      shifts.push_back(shift);
      if (mask == 0) break;
    }
  }
  // The position x + shift written over the record's position (its first field).
  static void write_shifted(const Vec<D>& x, const Vec<D>& shift, std::byte* out) {
    const Vec<D> y = x + shift;
    std::memcpy(out, y.data(), sizeof(Vec<D>));
  }
  std::size_t total_received(std::size_t rec) const {
    if (recv_.size() % rec != 0)
      throw std::runtime_error(
          "SlabExchange: records of another size arrived (optional fields differ between ranks)");
    return recv_.size() / rec;
  }

  Comm comm_;
  Slabs slabs_;
  double width_;
  long rebalance_every_, last_rebalance_ = -1;
  MigrationBuffers mig_;
  std::vector<std::uint32_t> send_lo_, send_hi_, slot_of_;
  std::vector<Vec<D>> shift_lo_, shift_hi_;  // per entry of send_lo_ / send_hi_ (periodic runs)
  std::size_t images_ = 0;                   // remote and own periodic images of the last build
  // Whether the grid has periodic axes, its domain and cell size (configure); ring_: the slab
  // axis is periodic.
  bool periodic_ = false, ring_ = false;
  Vec<D> dmin_ = Vec<D>::Zero(), dmax_ = Vec<D>::Zero();
  double cell_ = 0.0;
  std::vector<std::byte> send_, recv_;
  // The rebalance's work estimate (pair_work): per cell, then per particle.
  std::vector<std::uint32_t> work_all_, work_fluid_, work_;
  std::vector<Vec<D>> xs_;
  HaloStats stats_;
};

template <int D>
double SlabExchange<D>::wtime() {
  return static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                 std::chrono::steady_clock::now().time_since_epoch())
                                 .count()) *
         1e-9;
}

}  // namespace swell::parallel
