// Particle state as a structure of arrays with ONE field table.
//
// Every per-particle array is declared once, in SWELL_PARTICLE_FIELDS below: its name, element
// type, class (evolved state, integrator memory or constant) and its dataset name in snapshots.
// Everything that must treat all fields alike iterates the table through for_each_field():
// add(), reserve(), permute() (the reorder by cell), checkpoints and snapshots (io/hdf5_file),
// and later halo packing. Adding a field is one line in the table.
//
// Active particles occupy [0, size()); excluded particles are moved past the end by
// CellGrid::sort and stay there (counted, never simulated again). Reordering never allocates
// once the scratch buffers reached the particle count.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "solver/state/types.hpp"

namespace swell {

// What a field holds: evolved by the integrator, the integrator's memory of the last step, or
// set once (mass, role, body, id, reference position).
enum class FieldClass : std::uint8_t { State, Integrator, Constant };

struct FieldInfo {
  int index;         // position in the table
  const char* name;  // member name, also the dataset name in checkpoints
  FieldClass cls;
  const char* snapshot;  // dataset name in HDF5 snapshots; nullptr: not written there
  bool optional;         // empty unless enable()d (e.g. pos_ref: only runs with moving bodies)
};

// The field table. Columns: member, element type, class, snapshot dataset name, optional.
// Element types must be trivially copyable (they are stored raw in checkpoints).
#define SWELL_PARTICLE_FIELDS(X)                                                           \
  X(pos, V, FieldClass::State, "pos", false)                                               \
  X(vel, SV, FieldClass::State, "vel", false)                                              \
  X(rho, StateReal, FieldClass::State, "rho", false)                                       \
  /* integrator memory: v^n, rho^n (symplectic) or v^{n-1}, rho^{n-1} (Verlet); neither */ \
  /* reads x^n (the symplectic corrector drifts on from the predicted position)         */ \
  X(vel_prev, SV, FieldClass::Integrator, nullptr, false)                                  \
  X(rho_prev, StateReal, FieldClass::Integrator, nullptr, false)                           \
  X(mass, double, FieldClass::Constant, "mass", false)                                     \
  X(role, Role, FieldClass::Constant, "type", false)                                       \
  X(body, std::uint16_t, FieldClass::Constant, "body", false)                              \
  X(id, std::uint32_t, FieldClass::Constant, "id", false)                                  \
  /* the body-frame position a moving wall particle's motion law is applied to */          \
  X(pos_ref, V, FieldClass::Constant, nullptr, true)                                       \
  /* mDBC: vector from a wall particle to its wall surface (ghost node: pos + 2 normal) */ \
  X(normal, V, FieldClass::Constant, "normal", true)                                       \
  /* mDBC on a moving body: normal in the body frame */                                    \
  X(normal_ref, V, FieldClass::Constant, nullptr, true)                                    \
  /* mDBC's hydrostatic pressure on a moving body: the wall particle's acceleration, */    \
  /* set with its position at every substep by the motion hook (bc/moving_bodies.hpp) */   \
  X(wall_acc, V, FieldClass::Constant, nullptr, true)

// Arrays that are dead while the particles are reordered and may serve as the reorder's
// scratch: the vector one for the double vector fields, the double ones for the double scalar
// fields (the Simulation's force buffers at the start of an evaluation), the uint32 one for
// the ids (the cell grid's cell ids, recomputed after the reorder); the float fields go through
// their bytes afterwards (permute_raw). Lending them saves the set's own scratch.
template <int D>
struct LentScratch {
  std::vector<Vec<D>>* vec = nullptr;
  std::array<std::vector<double>*, 2> dbl{};
  std::vector<std::uint32_t>* u32 = nullptr;
};

template <int D>
struct ParticleSet {
  using V = Vec<D>;
  using SV = StateVec<D>;  // velocity storage (types.hpp: float unless SWELL_DOUBLE_STATE)

#define SWELL_DECLARE_FIELD(NAME, TYPE, CLS, SNAP, OPT) std::vector<TYPE> NAME;
  SWELL_PARTICLE_FIELDS(SWELL_DECLARE_FIELD)
#undef SWELL_DECLARE_FIELD

  std::size_t n_active = 0;
  // Periodic images (CellGrid::sort, periodic axes only) stored at [ghost_begin(), stored()):
  // copies of active particles within one kernel support of a periodic face, shifted by the
  // period. They exist only inside a step (read by the pair terms, never integrated, output or
  // saved); between steps n_ghost is 0.
  std::size_t n_ghost = 0;

  std::size_t size() const {
    return n_active;
  }
  // Active and excluded particles (everything that is output and saved).
  std::size_t total() const {
    return pos.size() - n_ghost;
  }
  std::size_t ghost_begin() const {
    return pos.size() - n_ghost;
  }
  // Every stored entry, ghosts included: the size per-particle buffers indexed by a pair's
  // neighbour must have.
  std::size_t stored() const {
    return pos.size();
  }

  // Calls fn(const FieldInfo&, array) for every field of the table, in table order, enabled
  // or not (a disabled optional field is an empty array).
  template <class Fn>
  void for_each_field(Fn&& fn) {
    int index = 0;
#define SWELL_VISIT_FIELD(NAME, TYPE, CLS, SNAP, OPT) \
  fn(FieldInfo{index++, #NAME, CLS, SNAP, OPT}, NAME);
    SWELL_PARTICLE_FIELDS(SWELL_VISIT_FIELD)
  }
  template <class Fn>
  void for_each_field(Fn&& fn) const {
    int index = 0;
    SWELL_PARTICLE_FIELDS(SWELL_VISIT_FIELD)
#undef SWELL_VISIT_FIELD
  }
  static constexpr int kNumFields = [] {
    int n = 0;
#define SWELL_COUNT_FIELD(NAME, TYPE, CLS, SNAP, OPT) ++n;
    SWELL_PARTICLE_FIELDS(SWELL_COUNT_FIELD)
#undef SWELL_COUNT_FIELD
    return n;
  }();

  // Particle i's stored velocity in double (the storage may be float: types.hpp).
  V velocity(std::size_t i) const {
    return widen<D>(vel[i]);
  }

  // Whether a field is in use (always, unless it is optional and not enabled).
  bool enabled(const FieldInfo& f) const {
    return !f.optional || enabled_[f.index];
  }
  // The same by name (false for an unknown name).
  bool enabled(const std::string& name) const {
    bool on = false;
    for_each_field([&](const FieldInfo& f, const auto&) {
      if (name == f.name) on = enabled(f);
    });
    return on;
  }
  // Turns an optional field on for every particle: a copy of `init` (same element type and
  // size), e.g. enable("pos_ref", pos). Throws for an unknown name or a mismatch.
  template <class T>
  void enable(const std::string& name, const std::vector<T>& init) {
    bool found = false;
    for_each_field([&](const FieldInfo& f, auto& a) {
      if (name != f.name) return;
      found = true;
      if constexpr (std::is_same_v<std::decay_t<decltype(a)>, std::vector<T>>) {
        if (init.size() != total())
          throw std::invalid_argument("ParticleSet::enable: '" + name + "' needs " +
                                      std::to_string(total()) + " values");
        a = init;
        enabled_[f.index] = true;
      } else {
        throw std::invalid_argument("ParticleSet::enable: wrong element type for '" + name + "'");
      }
    });
    if (!found) throw std::invalid_argument("ParticleSet::enable: no field '" + name + "'");
  }
  // Marks a field enabled whose array was filled from outside (checkpoint reader).
  void mark_enabled(const FieldInfo& f) {
    enabled_[f.index] = true;
  }

  void reserve(std::size_t n) {
    for_each_field([&](const FieldInfo& f, auto& a) {
      if (enabled(f)) a.reserve(n);
    });
  }

  // Appends one particle: every enabled field gets an entry; the integrator memory starts equal
  // to the state, the reference position equal to the position.
  void add(const V& x, const V& v, double density, double m, Role r, std::uint16_t body_id) {
    const auto next_id = static_cast<std::uint32_t>(pos.size());
    for_each_field([&](const FieldInfo& f, auto& a) {
      if (enabled(f)) a.emplace_back();
    });
    pos.back() = x;
    vel.back() = narrow<D>(v);
    rho.back() = static_cast<StateReal>(density);
    vel_prev.back() = vel.back();
    rho_prev.back() = rho.back();
    mass.back() = m;
    role.back() = r;
    body.back() = body_id;
    id.back() = next_id;
    if (!pos_ref.empty()) pos_ref.back() = x;
    if (!normal.empty()) normal.back() = V::Zero();
    if (!normal_ref.empty()) normal_ref.back() = V::Zero();
    if (!wall_acc.empty()) wall_acc.back() = V::Zero();
    n_active = pos.size();
  }

  // new[i] = old[order[i]] for every enabled field (order covers the active range; the
  // excluded tail keeps its place). Fields are gathered in passes: a pass takes, for each element
  // type, one field per scratch array of that type without barriers between them (one parallel
  // region), then swaps them in; the arrays left behind are the next pass's scratch. The
  // scratch arrays are the set's own (two per type) unless `lent` offers arrays that are dead
  // during this reorder: then those are used instead (they come back holding old field
  // contents and bytes, resized to total()) and the set's own are never allocated for that
  // type. The fields without typed scratch (float) follow through bytes (permute_raw).
  void permute(const std::vector<std::uint32_t>& order, const LentScratch<D>& lent = {}) {
    const long n = static_cast<long>(order.size());
    const std::size_t total_n = pos.size();
    for (int pass = 0;; ++pass) {
      bool any = false, later = false;
      visit_pass(pass, lent, [&](auto& a, auto& scratch, int p) {
        (void)a;
        if (p == pass) {
          scratch.resize(total_n);
          any = true;
        }
        later = later || p > pass;
      });
      if (!any) break;
#pragma omp parallel if (n > kParallelMin)
      visit_pass(pass, lent, [&](auto& a, auto& scratch, int p) {
        if (p != pass) return;
#pragma omp for schedule(static) nowait
        for (long i = 0; i < n; ++i) scratch[i] = a[order[i]];
      });
      visit_pass(pass, lent, [&](auto& a, auto& scratch, int p) {
        if (p != pass) return;
        for (std::size_t i = order.size(); i < total_n; ++i) scratch[i] = a[i];
        a.swap(scratch);
      });
      if (!later) break;
    }
    permute_raw(order, lent);
  }

  // Bytes of the set's own byte scratch (permute_raw): zero while lent arrays hold the float
  // fields (the time loop's sorts), which the tests check.
  std::size_t raw_scratch_bytes() const {
    return raw_.capacity();
  }

  // Frees the set's own scratch arrays (e.g. those a set-up sort allocated, before a Simulation
  // that lends its own takes the set over).
  void release_scratch() {
    scratch_ = Scratch{};
    raw_ = {};
    seen_ = {};
  }

  // The same reorder without any scratch array: each field is rearranged along the cycles of
  // `order` (serial, one bit per particle of bookkeeping). For the rare reorder between steps
  // (density exclusions), when the force buffers hold values that must stay readable: those
  // arrays are passed as `follow` and rearranged alike.
  void permute_in_place(const std::vector<std::uint32_t>& order,
                        std::vector<Vec<D>>* follow_vec = nullptr,
                        std::vector<double>* follow_dbl = nullptr) {
    for_each_field([&](const FieldInfo& f, auto& a) {
      if (enabled(f)) reorder_in_place(a, order);
    });
    if (follow_vec && follow_vec->size() >= order.size()) reorder_in_place(*follow_vec, order);
    if (follow_dbl && follow_dbl->size() >= order.size()) reorder_in_place(*follow_dbl, order);
  }

  // Below this many particles the O(N) loops of the sort run serially: their parallel
  // region would cost more than the loop.
  static constexpr long kParallelMin = 8192;

 private:
  static constexpr int kSlots = 2;
  template <class T>
  using Slots = std::array<std::vector<T>, kSlots>;
  using Scratch =
      std::tuple<Slots<V>, Slots<double>, Slots<Role>, Slots<std::uint16_t>, Slots<std::uint32_t>>;
  // Element types without typed scratch (the float state, types.hpp) are reordered through
  // bytes: see permute_raw.
  template <class T>
  static constexpr bool is_raw() {
    return type_slot<T>() < 0;
  }
  template <class T>
  static constexpr int type_slot() {
    if constexpr (std::is_same_v<T, V>) return 0;
    if constexpr (std::is_same_v<T, double>) return 1;
    if constexpr (std::is_same_v<T, Role>) return 2;
    if constexpr (std::is_same_v<T, std::uint16_t>) return 3;
    if constexpr (std::is_same_v<T, std::uint32_t>) return 4;
    return -1;
  }
  // new[i] = old[order[i]] for i < order.size(), following the permutation's cycles.
  template <class T>
  void reorder_in_place(std::vector<T>& a, const std::vector<std::uint32_t>& order) {
    const std::size_t n = order.size();
    seen_.assign((n + 63) / 64, 0);
    auto mark = [&](std::size_t i) { seen_[i / 64] |= std::uint64_t{1} << (i % 64); };
    auto marked = [&](std::size_t i) { return (seen_[i / 64] >> (i % 64)) & 1u; };
    for (std::size_t start = 0; start < n; ++start) {
      if (marked(start)) continue;
      mark(start);
      if (order[start] == start) continue;
      T first = a[start];
      std::size_t i = start;
      for (std::size_t next = order[i]; next != start; i = next, next = order[i]) {
        a[i] = a[next];
        mark(next);
      }
      a[i] = first;
    }
  }

  // The scratch arrays of element type T for this reorder: the lent ones if any were lent for
  // T, the set's own otherwise.
  template <class T>
  std::vector<T>* scratch_slot(const LentScratch<D>& lent, int k, int& slots) {
    if constexpr (std::is_same_v<T, V>) {
      if (lent.vec) {
        slots = 1;
        return lent.vec;
      }
    }
    if constexpr (std::is_same_v<T, double>) {
      const int nd = (lent.dbl[0] ? 1 : 0) + (lent.dbl[1] ? 1 : 0);
      if (nd > 0) {
        slots = nd;
        return lent.dbl[0] ? (k % nd == 0 ? lent.dbl[0] : lent.dbl[1]) : lent.dbl[1];
      }
    }
    if constexpr (std::is_same_v<T, std::uint32_t>) {
      if (lent.u32) {
        slots = 1;
        return lent.u32;
      }
    }
    slots = kSlots;
    return &std::get<Slots<T>>(scratch_)[static_cast<std::size_t>(k % kSlots)];
  }

  // Calls fn(array, its scratch array, its pass) for every enabled field. A field's pass is its
  // ordinal among the enabled fields of its element type, divided by the number of scratch
  // arrays of that type.
  template <class Fn>
  void visit_pass(int pass, const LentScratch<D>& lent, Fn&& fn) {
    int count[std::tuple_size_v<Scratch>] = {};
    for_each_field([&](const FieldInfo& f, auto& a) {
      using T = typename std::decay_t<decltype(a)>::value_type;
      if constexpr (is_raw<T>()) {
        return;
      } else {
        if (!enabled(f)) return;
        const int ordinal = count[type_slot<T>()]++;
        int slots = kSlots;
        std::vector<T>* scratch = scratch_slot<T>(lent, ordinal, slots);
        fn(a, *scratch, ordinal / slots);
      }
    });
    (void)pass;
  }

  // The reorder of the fields whose element type has no typed scratch (is_raw): each is
  // gathered, as bytes, into memory that is dead during this reorder (the lent arrays, which
  // the typed passes left holding old contents; the set's own byte array where they do not
  // suffice), then copied back. Lent arrays are resized to total() as in permute().
  void permute_raw(const std::vector<std::uint32_t>& order, const LentScratch<D>& lent) {
    const std::size_t n = order.size(), total_n = pos.size();
    struct Area {
      unsigned char* p;
      std::size_t bytes;
    };
    std::array<Area, 4> lent_areas{};
    int n_areas = 0;
    if (lent.vec) {
      lent.vec->resize(total_n);
      lent_areas[n_areas++] = {reinterpret_cast<unsigned char*>(lent.vec->data()),
                               total_n * sizeof(V)};
    }
    for (std::vector<double>* d : lent.dbl)
      if (d) {
        d->resize(total_n);
        lent_areas[n_areas++] = {reinterpret_cast<unsigned char*>(d->data()),
                                 total_n * sizeof(double)};
      }
    // Place each raw field, largest first (first fit decreasing: in 3D the two float vectors
    // then fill the lent vector array exactly and the float scalars a double array): the first
    // lent area with room left, else the set's own byte array.
    std::array<unsigned char*, kNumFields> where{};
    std::array<std::size_t, kNumFields> need{}, own_offset{};
    std::array<int, kNumFields> by_size{};
    int n_raw = 0;
    for_each_field([&](const FieldInfo& f, auto& a) {
      using T = typename std::decay_t<decltype(a)>::value_type;
      if constexpr (is_raw<T>()) {
        if (!enabled(f)) return;
        // (no padding: the element copies below are memcpy, which needs no alignment)
        need[f.index] = n * sizeof(T);
        by_size[n_raw++] = f.index;
      }
    });
    const bool any = n_raw > 0;
    std::stable_sort(by_size.begin(), by_size.begin() + n_raw,
                     [&](int a, int b) { return need[a] > need[b]; });
    std::array<std::size_t, 4> used{};
    std::size_t own_bytes = 0;
    for (int r = 0; r < n_raw; ++r) {
      const int k = by_size[r];
      for (int a = 0; a < n_areas && !where[k]; ++a)
        if (lent_areas[a].bytes - used[a] >= need[k]) {
          where[k] = lent_areas[a].p + used[a];
          used[a] += need[k];
        }
      if (!where[k]) {
        own_offset[k] = own_bytes;
        own_bytes += need[k];
      }
    }
    if (!any) return;
    if (raw_.size() < own_bytes) raw_.resize(own_bytes);
    for_each_field([&](const FieldInfo& f, auto& a) {
      using T = typename std::decay_t<decltype(a)>::value_type;
      if constexpr (is_raw<T>())
        if (enabled(f) && !where[f.index]) where[f.index] = raw_.data() + own_offset[f.index];
    });
    const long nl = static_cast<long>(n);
#pragma omp parallel if (nl > kParallelMin)
    {
      for_each_field([&](const FieldInfo& f, auto& a) {
        using T = typename std::decay_t<decltype(a)>::value_type;
        if constexpr (is_raw<T>()) {
          if (!enabled(f)) return;
          unsigned char* out = where[f.index];
#pragma omp for schedule(static) nowait
          for (long i = 0; i < nl; ++i) std::memcpy(out + i * sizeof(T), &a[order[i]], sizeof(T));
        }
      });
#pragma omp barrier
      for_each_field([&](const FieldInfo& f, auto& a) {
        using T = typename std::decay_t<decltype(a)>::value_type;
        if constexpr (is_raw<T>()) {
          if (!enabled(f)) return;
          const unsigned char* in = where[f.index];
#pragma omp for schedule(static) nowait
          for (long i = 0; i < nl; ++i)
            std::memcpy(static_cast<void*>(&a[i]), in + i * sizeof(T), sizeof(T));
        }
      });
    }
  }

  Scratch scratch_;
  std::vector<unsigned char> raw_;   // permute_raw's own byte scratch
  std::vector<std::uint64_t> seen_;  // permute_in_place's cycle marks
  std::array<bool, kNumFields> enabled_{};
};

}  // namespace swell
