// The decomposition's single-rank pieces (parallel/): a particle record packed from the field
// table comes back bit for bit, slab ownership, and the one-rank communicator (what a build
// without MPI, or a run without mpirun, uses) is the identity. The multi-rank tests are in
// tests/mpi/ (run through mpirun).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "parallel/comm.hpp"
#include "parallel/decomposition.hpp"
#include "solver/neighbours/cell_grid.hpp"

namespace swell::parallel {
namespace {

template <int D>
ParticleSet<D> random_set(std::size_t n, unsigned seed, bool optional) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto vec = [&] {
    Vec<D> v;
    for (int d = 0; d < D; ++d) v[d] = u(rng);
    return v;
  };
  ParticleSet<D> ps;
  for (std::size_t i = 0; i < n; ++i)
    ps.add(vec(), vec(), 1000.0 + u(rng), 0.1 + 0.01 * u(rng),
           i % 3 ? Role::Fluid : Role::MovingWall, static_cast<std::uint16_t>(i % 7));
  for (std::size_t i = 0; i < n; ++i)
    ps.vel_prev[i] = narrow<D>(vec()), ps.rho_prev[i] = 999.0 + u(rng);
  if (optional) {
    std::vector<Vec<D>> ref(n), nrm(n);
    for (std::size_t i = 0; i < n; ++i) ref[i] = vec(), nrm[i] = vec();
    ps.enable("pos_ref", ref);
    ps.enable("normal", nrm);
  }
  return ps;
}

template <int D>
void round_trip(bool optional) {
  const ParticleSet<D> a = random_set<D>(50, 7, optional);
  ParticleSet<D> b = random_set<D>(50, 8, optional);
  const std::size_t rec = record_bytes(a);
  // pos (V); vel, vel_prev (state vectors); rho, rho_prev (state scalars); mass (double); role,
  // body, id; + pos_ref, normal (V).
  const std::size_t expect = (optional ? 3 : 1) * sizeof(Vec<D>) + 2 * sizeof(StateVec<D>) +
                             2 * sizeof(StateReal) + sizeof(double) + sizeof(Role) +
                             sizeof(std::uint16_t) + sizeof(std::uint32_t);
  EXPECT_EQ(rec, expect);
  std::vector<std::byte> buf(rec);
  for (std::size_t i = 0; i < a.total(); ++i) {
    pack(a, i, buf.data());
    unpack(b, a.total() - 1 - i, buf.data());
  }
  for (std::size_t i = 0; i < a.total(); ++i) {
    const std::size_t j = a.total() - 1 - i;
    EXPECT_EQ(0, std::memcmp(&a.pos[i], &b.pos[j], sizeof(Vec<D>)));
    EXPECT_EQ(0, std::memcmp(&a.vel_prev[i], &b.vel_prev[j], sizeof(StateVec<D>)));
    EXPECT_EQ(0, std::memcmp(&a.rho_prev[i], &b.rho_prev[j], sizeof(StateReal)));
    EXPECT_EQ(a.role[i], b.role[j]);
    EXPECT_EQ(a.body[i], b.body[j]);
    EXPECT_EQ(a.id[i], b.id[j]);
    if (optional) {
      EXPECT_EQ(a.pos_ref[i], b.pos_ref[j]);
      EXPECT_EQ(a.normal[i], b.normal[j]);
    }
  }
}

TEST(ParallelRecord, RoundTripIsExact2D) {
  round_trip<2>(false);
  round_trip<2>(true);
}
TEST(ParallelRecord, RoundTripIsExact3D) {
  round_trip<3>(false);
  round_trip<3>(true);
}

TEST(ParallelSlabs, OwnerFollowsTheBounds) {
  const Slabs s = even_slabs(1, 0.0, 1.0, 4);
  EXPECT_EQ(s.size(), 4);
  EXPECT_EQ(s.owner(-5.0), 0);  // beyond the domain: the end slabs (the sort excludes it)
  EXPECT_EQ(s.owner(0.1), 0);
  EXPECT_EQ(s.owner(0.25), 1);  // a bound belongs to the slab above it
  EXPECT_EQ(s.owner(0.6), 2);
  EXPECT_EQ(s.owner(0.99), 3);
  EXPECT_EQ(s.owner(1e9), 3);
  EXPECT_EQ(longest_axis<3>(Vec<3>(0, 0, 0), Vec<3>(1, 3, 2)), 1);
}

TEST(ParallelComm, OneRankIsTheIdentity) {
  const Comm c = Comm::self();
  EXPECT_EQ(c.rank(), 0);
  EXPECT_EQ(c.size(), 1);
  EXPECT_EQ(c.min(2.5), 2.5);
  EXPECT_EQ(c.sum(std::uint64_t{7}), 7u);
  std::vector<std::byte> send{std::byte{1}, std::byte{2}}, recv;
  std::vector<int> count{2}, rc, rd;
  c.alltoallv(send, count, recv, rc, rd);
  EXPECT_EQ(recv, send);
  // Without mpirun the world is one rank too.
  EXPECT_EQ(Comm::world().size(), 1);
}

TEST(ParallelMigrate, OneRankChangesNothing) {
  ParticleSet<2> ps = random_set<2>(40, 3, true);
  ps.n_active -= 4;  // four excluded particles at the end
  const ParticleSet<2> before = ps;
  MigrationBuffers buf;
  migrate(ps, even_slabs(0, -1.0, 1.0, 1), Comm::self(), buf);
  EXPECT_EQ(buf.sent, 0u);
  EXPECT_EQ(ps.n_active, before.n_active);
  EXPECT_EQ(ps.pos, before.pos);
  EXPECT_EQ(ps.id, before.id);
  EXPECT_EQ(ps.pos_ref, before.pos_ref);
  // The minimum width is checked before anything else.
  EXPECT_THROW(balanced_slabs(ps, 0, 0.0, 0.05, 0.1, Comm::self()), std::invalid_argument);
  const Slabs one = balanced_slabs(ps, 0, -1.0, 1.0, 0.1, Comm::self());
  ASSERT_EQ(one.lo.size(), 2u);
  EXPECT_EQ(one.lo[0], -1.0);
  EXPECT_EQ(one.lo[1], 1.0);
  EXPECT_EQ(imbalance(ps, Comm::self()), 1.0);
}

// pair_work counts what the pair loop visits: for every particle, the candidates of the cell
// grid around it (CellGrid::for_each_candidate_near, the same cells), and nothing for a wall in
// a cell with no fluid around (the loop skips it) or a particle outside the domain.
template <int D>
void pair_work_matches_the_grid() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ParticleSet<D> ps;
  for (int i = 0; i < 600; ++i) {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = u(rng);
    // Fluid in the lower half only, so some wall cells in the upper half are dry.
    const bool fluid = i % 2 == 0;
    if (fluid) x[D - 1] *= 0.5;
    ps.add(x, Vec<D>::Zero(), 1000.0, 0.1, fluid ? Role::Fluid : Role::FixedWall, 0);
  }
  Vec<D> outside = Vec<D>::Constant(0.5);
  outside[0] = 1.5;
  ps.add(outside, Vec<D>::Zero(), 1000.0, 0.1, Role::Fluid, 0);
  const Vec<D> lo = Vec<D>::Zero(), hi = Vec<D>::Ones();
  const double cell = 0.13;
  std::vector<std::uint32_t> all, fluid, weight;
  pair_work(ps, lo, hi, cell, all, fluid, weight);
  ASSERT_EQ(weight.size(), ps.size());
  EXPECT_EQ(weight.back(), 0u) << "a particle outside the domain weighs nothing";
  CellGrid<D> grid(lo, hi, cell);
  ParticleSet<D> sorted = ps;
  grid.sort(sorted);
  std::vector<std::uint32_t> expect(ps.size(), 0);
  std::size_t dry_walls = 0;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    std::uint32_t n_all = 0, n_fluid = 0;
    grid.for_each_candidate_near(sorted.pos[i], [&](std::uint32_t j) {
      ++n_all;
      n_fluid += is_fluid(sorted.role[j]);
    });
    const std::uint32_t seen = is_fluid(sorted.role[i]) ? n_all : n_fluid;
    if (n_fluid == 0) {
      ++dry_walls;
      EXPECT_FALSE(grid.fluid_near(grid.cell_of(i)));
    }
    expect[sorted.id[i]] = n_fluid == 0 ? 0 : n_all + static_cast<std::uint32_t>(4 - D) * seen;
  }
  EXPECT_GT(dry_walls, 0u) << "the set should hold dry walls";
  for (std::size_t i = 0; i + 1 < ps.size(); ++i) EXPECT_EQ(weight[i], expect[ps.id[i]]) << i;
}

TEST(ParallelBalance, PairWorkCountsWhatThePairLoopVisits2D) {
  pair_work_matches_the_grid<2>();
}
TEST(ParallelBalance, PairWorkCountsWhatThePairLoopVisits3D) {
  pair_work_matches_the_grid<3>();
}

// Weighted slabs split the summed weight, not the count: all the weight on x > 0.5 puts both
// halves of it on either side of the cut.
TEST(ParallelBalance, WeightedSlabsSplitTheWeight) {
  ParticleSet<2> ps;
  std::vector<std::uint32_t> w;
  for (int i = 0; i < 100; ++i) {
    const double x = (i + 0.5) / 100.0;
    ps.add(Vec<2>(x, 0.5), Vec<2>::Zero(), 1000.0, 0.1, Role::Fluid, 0);
    w.push_back(x > 0.5 ? 3u : 0u);
  }
  const Slabs counted = balanced_slabs(ps, 0, 0.0, 1.0, 0.05, Comm::self(), 1000, 2);
  const Slabs weighted = balanced_slabs(ps, 0, 0.0, 1.0, 0.05, Comm::self(), 1000, 2, true, &w);
  EXPECT_NEAR(counted.lo[1], 0.5, 0.01);
  EXPECT_NEAR(weighted.lo[1], 0.75, 0.01);
  // No weight anywhere: the fluid count again.
  std::vector<std::uint32_t> none(w.size(), 0u);
  EXPECT_NEAR(balanced_slabs(ps, 0, 0.0, 1.0, 0.05, Comm::self(), 1000, 2, true, &none).lo[1], 0.5,
              0.01);
  std::vector<std::uint32_t> short_list(3, 1u);
  EXPECT_THROW(balanced_slabs(ps, 0, 0.0, 1.0, 0.05, Comm::self(), 1000, 2, true, &short_list),
               std::logic_error);
}

}  // namespace
}  // namespace swell::parallel
