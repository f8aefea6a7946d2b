// CellGrid<D> (solver/cell_grid.hpp) against brute force: after sort() the candidates of every
// particle, filtered by distance < cell size, are exactly the brute-force neighbours; the sort is
// a consistent permutation ordered by cell; out-of-domain and non-finite particles are excluded,
// counted and parked past size(); a second sort is a no-op; probes at arbitrary points agree too.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/state/types.hpp"

namespace swell {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

template <int D>
Vec<D> filled(double a) {
  return Vec<D>::Constant(a);
}

// A box whose sides are not multiples of the cell size, so the last cell row is partial.
template <int D>
struct Box {
  Vec<D> lo, hi;
  double cell = 0.071;
  Box() {
    for (int d = 0; d < D; ++d) {
      lo[d] = -0.3 + 0.1 * d;
      hi[d] = 0.85 + 0.13 * d;
    }
  }
};

// Each particle's per-particle data is derived from its id so a wrong permutation shows up.
template <int D>
void add_particle(ParticleSet<D>& ps, const std::type_identity_t<Vec<D>>& x) {
  const double id = static_cast<double>(ps.total());
  Vec<D> v;
  for (int d = 0; d < D; ++d) v[d] = id + 0.25 * d;
  ps.add(x, v, 1000.0 + id, 0.5 * id, ps.total() % 3 == 0 ? Role::FixedWall : Role::Fluid,
         static_cast<std::uint16_t>(ps.total() % 7));
}

// Random particles inside the box: a uniform background, two dense clusters (many particles per
// cell, exact duplicates included) and particles exactly on the domain faces and corners.
template <int D>
void add_inside(ParticleSet<D>& ps, const Box<D>& box, std::mt19937_64& rng, int n_uniform) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto uniform_point = [&] {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = box.lo[d] + u(rng) * (box.hi[d] - box.lo[d]);
    return x;
  };
  for (int k = 0; k < n_uniform; ++k) add_particle(ps, uniform_point());
  for (int c = 0; c < 2; ++c) {
    const Vec<D> centre =
        c == 0 ? Vec<D>(0.5 * (box.lo + box.hi)) : Vec<D>(box.lo + filled<D>(0.05));
    for (int k = 0; k < 400; ++k) {
      Vec<D> x;
      for (int d = 0; d < D; ++d) x[d] = centre[d] + (u(rng) - 0.5) * 1.5 * box.cell;
      if (k % 50 == 0 && k > 0) x = ps.pos.back();  // exact duplicate of the previous particle
      add_particle(ps, x.cwiseMax(box.lo).cwiseMin(box.hi));
    }
  }
  add_particle(ps, box.lo);
  add_particle(ps, box.hi);
  for (int k = 0; k < 20; ++k) {  // on a face: one coordinate exactly at lo or hi
    Vec<D> x = uniform_point();
    x[k % D] = (k / D) % 2 == 0 ? box.lo[k % D] : box.hi[k % D];
    add_particle(ps, x);
  }
}

// Ids of the active particles within distance r of x, by brute force.
template <int D>
std::vector<std::uint32_t> brute_force(const ParticleSet<D>& ps, const Vec<D>& x, double r) {
  std::vector<std::uint32_t> ids;
  for (std::size_t j = 0; j < ps.size(); ++j)
    if ((ps.pos[j] - x).norm() < r) ids.push_back(ps.id[j]);
  std::sort(ids.begin(), ids.end());
  return ids;
}

// Same set through the grid; also fails on a candidate outside the active range or one visited
// twice (the neighbour ranges of one cell must not overlap).
template <int D, class ForEach>
std::vector<std::uint32_t> through_grid(const ParticleSet<D>& ps, const Vec<D>& x, double r,
                                        ForEach&& for_each) {
  std::vector<std::uint32_t> candidates, ids;
  for_each([&](std::uint32_t j) { candidates.push_back(j); });
  for (std::uint32_t j : candidates) {
    EXPECT_LT(j, ps.size());
    if (j < ps.size() && (ps.pos[j] - x).norm() < r) ids.push_back(ps.id[j]);
  }
  std::sort(candidates.begin(), candidates.end());
  EXPECT_EQ(std::adjacent_find(candidates.begin(), candidates.end()), candidates.end())
      << "a candidate was visited twice";
  std::sort(ids.begin(), ids.end());
  return ids;
}

// Every particle's data is still the data created with its id.
template <int D>
void expect_consistent(const ParticleSet<D>& ps, const std::vector<Vec<D>>& original_pos) {
  std::vector<std::uint32_t> ids(ps.id.begin(), ps.id.end());
  std::sort(ids.begin(), ids.end());
  for (std::size_t k = 0; k < ids.size(); ++k) ASSERT_EQ(ids[k], k) << "ids are not a permutation";
  for (std::size_t k = 0; k < ps.total(); ++k) {
    const std::uint32_t id = ps.id[k];
    const bool same_pos = (ps.pos[k].array() == original_pos[id].array()).all() ||
                          (ps.pos[k].array().isNaN() && original_pos[id].array().isNaN()).any();
    EXPECT_TRUE(same_pos) << "slot " << k;
    EXPECT_EQ(ps.vel[k][0], static_cast<double>(id)) << "slot " << k;
    EXPECT_EQ(ps.mass[k], 0.5 * id);
    EXPECT_EQ(ps.body[k], id % 7);
    EXPECT_EQ(ps.role[k], id % 3 == 0 ? Role::FixedWall : Role::Fluid);
    EXPECT_EQ(ps.id[k], id);
  }
}

template <class T>
class CellGridTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
struct DimName {
  template <class T>
  static std::string GetName(int) {
    return std::to_string(T::value) + "D";
  }
};
TYPED_TEST_SUITE(CellGridTest, Dims, DimName);

TYPED_TEST(CellGridTest, NeighboursMatchBruteForce) {
  constexpr int D = TypeParam::value;
  const Box<D> box;
  std::mt19937_64 rng(20240611 + D);
  ParticleSet<D> ps;
  add_inside(ps, box, rng, D == 2 ? 3000 : 4000);
  const std::vector<Vec<D>> original(ps.pos.begin(), ps.pos.end());
  const std::size_t n = ps.size();

  CellGrid<D> grid(box.lo, box.hi, box.cell);
  const auto res = grid.sort(ps);
  EXPECT_EQ(res.out_of_domain, 0u);
  EXPECT_EQ(res.non_finite, 0u);
  ASSERT_EQ(ps.size(), n);
  ASSERT_EQ(ps.total(), n);
  expect_consistent(ps, original);

  // Ordered by cell, and cell_of / begin / end agree with the positions.
  for (std::size_t i = 0; i < ps.size(); ++i) {
    EXPECT_EQ(grid.cell_of(i), grid.cell_index(ps.pos[i])) << "i=" << i;
    if (i > 0) {
      EXPECT_LE(grid.cell_of(i - 1), grid.cell_of(i)) << "i=" << i;
    }
    EXPECT_GE(i, grid.begin(grid.cell_of(i)));
    EXPECT_LT(i, grid.end(grid.cell_of(i)));
  }

  std::size_t pairs = 0, max_neigh = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const auto expected = brute_force(ps, ps.pos[i], box.cell);
    const auto found =
        through_grid(ps, ps.pos[i], box.cell, [&](auto fn) { grid.for_each_candidate(i, fn); });
    ASSERT_EQ(found, expected) << "particle id " << ps.id[i];
    pairs += found.size();
    max_neigh = std::max(max_neigh, found.size());
  }
  // Not vacuous: the clusters give cells with many particles and every particle sees itself.
  EXPECT_GT(pairs, 2 * n);
  EXPECT_GT(max_neigh, 100u);
}

TYPED_TEST(CellGridTest, ExcludesOutOfDomainAndNonFinite) {
  constexpr int D = TypeParam::value;
  const Box<D> box;
  std::mt19937_64 rng(77 + D);
  ParticleSet<D> ps;
  add_inside(ps, box, rng, 1500);
  const std::size_t n_in = ps.total();
  std::vector<std::uint32_t> bad_domain, bad_value;
  // Out of the domain, on every side and just past the faces.
  for (int d = 0; d < D; ++d) {
    Vec<D> x = 0.5 * (box.lo + box.hi);
    x[d] = std::nextafter(box.hi[d], kInf);
    bad_domain.push_back(static_cast<std::uint32_t>(ps.total()));
    add_particle(ps, x);
    x[d] = box.lo[d] - 3.0;
    bad_domain.push_back(static_cast<std::uint32_t>(ps.total()));
    add_particle(ps, x);
  }
  // Non-finite position, velocity or density (a NaN position also fails the domain test; it
  // must be counted once, as non-finite).
  {
    Vec<D> x = 0.5 * (box.lo + box.hi);
    x[D - 1] = kNaN;
    bad_value.push_back(static_cast<std::uint32_t>(ps.total()));
    add_particle(ps, x);
    bad_value.push_back(static_cast<std::uint32_t>(ps.total()));
    add_particle(ps, 0.5 * (box.lo + box.hi));
    ps.vel.back()[D - 1] = kInf;  // component 0 keeps the id check
    bad_value.push_back(static_cast<std::uint32_t>(ps.total()));
    add_particle(ps, 0.5 * (box.lo + box.hi));
    ps.rho.back() = kNaN;
    ps.rho_prev.back() = kNaN;
  }
  // More valid particles after the bad ones, so exclusion really has to move things.
  add_inside(ps, box, rng, 500);
  const std::vector<Vec<D>> original(ps.pos.begin(), ps.pos.end());
  const std::size_t total = ps.total();
  const std::size_t n_bad = bad_domain.size() + bad_value.size();

  CellGrid<D> grid(box.lo, box.hi, box.cell);
  const auto res = grid.sort(ps);
  EXPECT_EQ(res.out_of_domain, bad_domain.size());
  EXPECT_EQ(res.non_finite, bad_value.size());
  EXPECT_EQ(ps.size(), total - n_bad);
  EXPECT_EQ(ps.total(), total);
  EXPECT_GT(ps.size(), n_in);
  expect_consistent(ps, original);

  // The excluded particles are exactly the ones past size().
  std::vector<std::uint32_t> parked(ps.id.begin() + ps.size(), ps.id.end()), bad = bad_domain;
  bad.insert(bad.end(), bad_value.begin(), bad_value.end());
  std::sort(parked.begin(), parked.end());
  std::sort(bad.begin(), bad.end());
  EXPECT_EQ(parked, bad);

  // Neighbour sets still match brute force (which sees only the active range).
  for (std::size_t i = 0; i < ps.size(); i += 7) {
    const auto found =
        through_grid(ps, ps.pos[i], box.cell, [&](auto fn) { grid.for_each_candidate(i, fn); });
    ASSERT_EQ(found, brute_force(ps, ps.pos[i], box.cell)) << "particle id " << ps.id[i];
  }
}

TYPED_TEST(CellGridTest, SecondSortIsNoOpAndResortAfterMotion) {
  constexpr int D = TypeParam::value;
  const Box<D> box;
  std::mt19937_64 rng(99 + D);
  ParticleSet<D> ps;
  add_inside(ps, box, rng, 2000);
  Vec<D> outside = box.hi + filled<D>(1.0);
  add_particle(ps, outside);

  CellGrid<D> grid(box.lo, box.hi, box.cell);
  const auto first = grid.sort(ps);
  EXPECT_EQ(first.out_of_domain, 1u);
  const std::vector<std::uint32_t> ids_after_first(ps.id.begin(), ps.id.end());
  const std::size_t active = ps.size();

  // The counting sort is stable, so sorting sorted particles changes nothing; the excluded one
  // stays parked and is not counted again.
  const auto second = grid.sort(ps);
  EXPECT_EQ(second.out_of_domain, 0u);
  EXPECT_EQ(second.non_finite, 0u);
  EXPECT_EQ(ps.size(), active);
  EXPECT_EQ(std::vector<std::uint32_t>(ps.id.begin(), ps.id.end()), ids_after_first);

  // Move every particle by up to one cell (some leave the domain) and sort again.
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (int d = 0; d < D; ++d) ps.pos[i][d] += u(rng) * box.cell;
  std::size_t leaving = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) leaving += grid.inside_domain(ps.pos[i]) ? 0 : 1;
  ASSERT_GT(leaving, 0u);
  const auto third = grid.sort(ps);
  EXPECT_EQ(third.out_of_domain, leaving);
  EXPECT_EQ(ps.size(), active - leaving);
  for (std::size_t i = 1; i < ps.size(); ++i) EXPECT_LE(grid.cell_of(i - 1), grid.cell_of(i));
  for (std::size_t i = 0; i < ps.size(); i += 5) {
    const auto found =
        through_grid(ps, ps.pos[i], box.cell, [&](auto fn) { grid.for_each_candidate(i, fn); });
    ASSERT_EQ(found, brute_force(ps, ps.pos[i], box.cell)) << "particle id " << ps.id[i];
  }
}

// The parallel counting sort (each thread histograms and scatters the particles of its static
// share) gives the serial sort's order whatever the thread count: here 1, 2, 3 and 4 threads on
// 12,000 particles in random order (each thread's cells spread over the whole grid: the widest
// histograms), with out-of-domain and non-finite ones, then again after a move of up to a
// cell (the time loop's case: narrow, overlapping ranges). The order is checked against a
// stable sort by cell of the previous order; thread_cells splits the cells where the static
// schedule splits the particles.
TYPED_TEST(CellGridTest, ParallelSortIsTheSerialOneAtAnyThreadCount) {
  constexpr int D = TypeParam::value;
  const Box<D> box;
  std::mt19937_64 rng(31 + D);
  ParticleSet<D> base;
  add_inside(base, box, rng, 11000);  // above ParticleSet::kParallelMin: the parallel sort
  std::vector<std::size_t> perm(base.total());
  for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), rng);
  ParticleSet<D> shuffled;
  for (std::size_t k : perm) add_particle(shuffled, base.pos[k]);  // ids in shuffled order
  add_particle(shuffled, box.hi + filled<D>(1.0));
  add_particle(shuffled, 0.5 * (box.lo + box.hi));
  shuffled.rho.back() = kNaN;
  ASSERT_GT(static_cast<long>(shuffled.total()), ParticleSet<D>::kParallelMin);
  const int threads_before = omp_get_max_threads();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec<D>> moves(shuffled.total());
  for (auto& m : moves)
    for (int d = 0; d < D; ++d) m[d] = u(rng) * box.cell;
  for (int nt = 1; nt <= 4; ++nt) {
    omp_set_num_threads(nt);
    ParticleSet<D> ps = shuffled;
    CellGrid<D> grid(box.lo, box.hi, box.cell);
    for (int round = 0; round < 2; ++round) {
      // The expected order: stable by cell (excluded last) of the order before this sort.
      const std::size_t n = ps.size();
      std::vector<std::uint32_t> key(n);
      std::size_t n_in = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const bool ok =
            ps.pos[i].allFinite() && std::isfinite(ps.rho[i]) && grid.inside_domain(ps.pos[i]);
        key[i] = ok ? grid.cell_index(ps.pos[i]) : std::numeric_limits<std::uint32_t>::max();
        n_in += ok;
      }
      std::vector<std::uint32_t> expect(n);
      for (std::size_t i = 0; i < n; ++i) expect[i] = static_cast<std::uint32_t>(i);
      std::stable_sort(expect.begin(), expect.end(),
                       [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
      for (auto& e : expect) e = ps.id[e];
      const auto r = grid.sort(ps);
      ASSERT_EQ(ps.size(), n_in) << nt << " threads, round " << round;
      EXPECT_EQ(r.non_finite, round == 0 ? 1u : 0u);
      EXPECT_EQ(std::vector<std::uint32_t>(ps.id.begin(), ps.id.begin() + n), expect)
          << nt << " threads, round " << round;
      for (std::size_t c = 0; c < grid.num_cells(); ++c)
        for (std::uint32_t i = grid.begin(c); i < grid.end(c); ++i)
          ASSERT_EQ(grid.cell_of(i), c) << nt << " threads, round " << round;
      // thread_cells: contiguous, covering every cell once, split at the static shares.
      for (int k = 1; k <= 4; ++k) {
        long expect_first = 0;
        for (int t = 0; t < k; ++t) {
          long first = -1, last = -1;
          grid.thread_cells(t, k, first, last);
          ASSERT_EQ(first, expect_first) << "thread " << t << " of " << k;
          ASSERT_LE(first, last);
          const std::size_t share = ps.size() / k * t + std::min<std::size_t>(t, ps.size() % k);
          if (t > 0) {
            EXPECT_GE(grid.begin(first), share);
            EXPECT_LT(grid.begin(first - 1), share);
          }
          expect_first = last;
        }
        EXPECT_EQ(expect_first, static_cast<long>(grid.num_cells()));
      }
      for (std::size_t i = 0; i < ps.size(); ++i) ps.pos[i] += moves[ps.id[i]];
    }
  }
  omp_set_num_threads(threads_before);
}

TYPED_TEST(CellGridTest, CandidatesNearArbitraryPoints) {
  constexpr int D = TypeParam::value;
  const Box<D> box;
  std::mt19937_64 rng(4242 + D);
  ParticleSet<D> ps;
  add_inside(ps, box, rng, 3000);
  CellGrid<D> grid(box.lo, box.hi, box.cell);
  grid.sort(ps);

  std::uniform_real_distribution<double> u(0.0, 1.0);
  int probes_with_neighbours = 0;
  for (int k = 0; k < 2000; ++k) {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = box.lo[d] + u(rng) * (box.hi[d] - box.lo[d]);
    if (k < 2 * D) x[k % D] = k < D ? box.lo[k % D] : box.hi[k % D];  // probes on the faces
    const auto found =
        through_grid(ps, x, box.cell, [&](auto fn) { grid.for_each_candidate_near(x, fn); });
    const auto expected = brute_force(ps, x, box.cell);
    ASSERT_EQ(found, expected) << "probe " << k;
    probes_with_neighbours += expected.empty() ? 0 : 1;
  }
  EXPECT_GT(probes_with_neighbours, 1000);

  // Documented behaviour: a point outside the domain (or NaN) gets no candidates at all.
  for (const Vec<D>& x :
       {Vec<D>(box.hi + filled<D>(0.01)), Vec<D>(box.lo - filled<D>(0.5)), filled<D>(kNaN)}) {
    int calls = 0;
    grid.for_each_candidate_near(x, [&](std::uint32_t) { ++calls; });
    EXPECT_EQ(calls, 0);
  }
}

TEST(CellGrid, RejectsEmptyDomain) {
  EXPECT_THROW(CellGrid<2>(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.0), 0.1), std::invalid_argument);
  EXPECT_THROW(CellGrid<3>(Vec<3>(0.0, 0.0, 0.0), Vec<3>(1.0, 1.0, kNaN), 0.1),
               std::invalid_argument);
}

// The three ways sort() rearranges the arrays (the set's own scratch, scratch lent by the
// caller, in place along the permutation's cycles) give the same set, field for field, with
// optional fields enabled and particles leaving; lent arrays come back sized to the set, and
// in place the `follow` arrays move with their particles.
TYPED_TEST(CellGridTest, ReorderModesAgree) {
  constexpr int D = TypeParam::value;
  const Box<D> box;
  std::mt19937_64 rng(7 + D);
  ParticleSet<D> own;
  add_inside(own, box, rng, 5000);  // above ParticleSet::kParallelMin: the parallel gather
  add_particle(own, box.hi + filled<D>(1.0));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < own.total(); ++i) {
    for (int d = 0; d < D; ++d) own.vel[i][d] = u(rng), own.vel_prev[i][d] = u(rng);
    own.rho[i] = 1000.0 + u(rng), own.rho_prev[i] = 1000.0 + u(rng), own.mass[i] = 1.0 + u(rng);
    own.body[i] = static_cast<std::uint16_t>(i % 7);
    own.role[i] = i % 3 ? Role::Fluid : Role::FixedWall;
  }
  std::vector<Vec<D>> ref(own.total()), nrm(own.total());
  for (std::size_t i = 0; i < own.total(); ++i)
    ref[i] = widen<D>(own.vel[i]) + filled<D>(2.0), nrm[i] = widen<D>(own.vel_prev[i]);
  own.enable("pos_ref", ref);
  own.enable("normal", nrm);
  ParticleSet<D> lent_set = own, in_place_set = own;
  // Follow arrays: a value that identifies its particle (the id, and minus the id).
  std::vector<Vec<D>> follow_v(own.total());
  std::vector<double> follow_d(own.total());
  for (std::size_t i = 0; i < own.total(); ++i) {
    follow_v[i] = filled<D>(static_cast<double>(own.id[i]));
    follow_d[i] = -static_cast<double>(own.id[i]);
  }

  CellGrid<D> g1(box.lo, box.hi, box.cell), g2 = g1, g3 = g1;
  std::vector<Vec<D>> sv(3, Vec<D>::Zero());  // too small: permute sizes them
  std::vector<double> sd1, sd2(10 * own.total(), 0.0);
  typename CellGrid<D>::Reorder lent;
  lent.lent.vec = &sv;
  lent.lent.dbl = {&sd1, &sd2};
  typename CellGrid<D>::Reorder cycles;
  cycles.in_place = true;
  cycles.follow_vec = &follow_v;
  cycles.follow_dbl = &follow_d;
  for (int round = 0; round < 3; ++round) {
    const auto r1 = g1.sort(own);
    const auto r2 = g2.sort(lent_set, lent);
    const auto r3 = g3.sort(in_place_set, cycles);
    EXPECT_EQ(r1.out_of_domain, r2.out_of_domain);
    EXPECT_EQ(r1.out_of_domain, r3.out_of_domain);
    ASSERT_EQ(own.size(), lent_set.size());
    ASSERT_EQ(own.size(), in_place_set.size());
    own.for_each_field([&](const FieldInfo& f, const auto& a) {
      lent_set.for_each_field([&](const FieldInfo& f2, const auto& b) {
        if constexpr (std::is_same_v<decltype(a), decltype(b)>)
          if (f.index == f2.index) EXPECT_TRUE(a == b) << "lent scratch, field " << f.name;
      });
      in_place_set.for_each_field([&](const FieldInfo& f2, const auto& b) {
        if constexpr (std::is_same_v<decltype(a), decltype(b)>)
          if (f.index == f2.index) EXPECT_TRUE(a == b) << "in place, field " << f.name;
      });
    });
    EXPECT_EQ(sv.size(), own.total());
    // The float fields (if any) went through the lent arrays' bytes, none of the set's own.
    EXPECT_EQ(lent_set.raw_scratch_bytes(), 0u);
    EXPECT_EQ(sd1.size(), own.total());
    EXPECT_EQ(sd2.size(), own.total());
    for (std::size_t i = 0; i < in_place_set.size(); ++i) {
      ASSERT_EQ(follow_v[i], filled<D>(static_cast<double>(in_place_set.id[i]))) << i;
      ASSERT_EQ(follow_d[i], -static_cast<double>(in_place_set.id[i])) << i;
    }
    // Move everything by up to a cell for the next round (some particles leave).
    for (ParticleSet<D>* ps : {&own, &lent_set, &in_place_set}) {
      std::mt19937_64 same(100 + static_cast<unsigned>(round));
      for (std::size_t i = 0; i < ps->size(); ++i)
        for (int d = 0; d < D; ++d) ps->pos[i][d] += u(same) * 0.7 * box.cell;
    }
  }
}

}  // namespace
}  // namespace swell
