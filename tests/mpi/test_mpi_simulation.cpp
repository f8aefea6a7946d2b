// The time loop on several ranks (run by ctest through mpirun, 1, 2 and 3 ranks): the 2D dam
// break of cases/dambreak2d.yaml (a/dp = 20) stepped with the slab decomposition (slabs along
// x, halo exchange, migration, rebalancing) against the same run on one rank (computed on
// every rank, no exchange), particle by particle by id after 300 steps.
//
// Why the runs differ at all: a particle's neighbours come in another order on several ranks
// (the halo images follow the stored particles), so its sums are added in another order and
// differ in the last bits. With a fixed time step that is all (bounds at rounding level). With
// the CFL step, see kVarDx. Every particle must arrive exactly once with its constants, and
// for a fixed number of ranks the run is deterministic: two runs agree bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <type_traits>
#include <vector>

#include "case/reader.hpp"
#include "case/setup.hpp"
#include "parallel/comm.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/halo.hpp"
#include "run/rank_setup.hpp"
#include "verify/pair_rounding.hpp"

namespace swell::parallel {
namespace {

constexpr int kSteps = 300;

CaseSetup<2> dam_break(const std::vector<std::string>& sets) {
  std::vector<std::string> all = {"dp=0.0028575", "time.end=1"};
  all.insert(all.end(), sets.begin(), sets.end());
  return setup_case<2>(load_case_file(SWELL_SOURCE_DIR "/cases/dambreak2d.yaml", all));
}

struct Decomposed {
  ParticleSet<2> gathered;  // rank 0 only
  double time = 0.0;
  HaloStats stats;  // summed over ranks
};

// The case on every rank of the world, slabs along `axis`, rebalanced every `rebalance` steps.
Decomposed run_decomposed(const CaseSetup<2>& setup, int steps, long rebalance,
                          double width_factor = 1.0, int axis = 0) {
  const Comm comm = Comm::world();
  const double width = halo_width(setup.params, setup.particles) * width_factor;
  const Slabs slabs =
      balanced_slabs(setup.particles, axis, setup.params.domain_min[axis],
                     setup.params.domain_max[axis], width, Comm::self(), 4096, comm.size(), true);
  auto ex = std::make_unique<SlabExchange<2>>(comm, slabs, width, rebalance);
  const SlabExchange<2>* exch = ex.get();
  Simulation<2> sim =
      make_simulation<2>(setup, share_by_slabs(setup.particles, slabs, comm.rank()), std::move(ex));
  for (int s = 0; s < steps; ++s) sim.step();
  Decomposed d;
  GatherBuffers buf;
  gather_to_root<2>(sim.particles(), comm, d.gathered, nullptr, nullptr, buf);
  d.time = sim.time();
  d.stats.images = comm.sum(static_cast<std::uint64_t>(exch->stats().images));
  d.stats.migrated = comm.sum(static_cast<std::uint64_t>(exch->stats().migrated));
  d.stats.rebalances = exch->stats().rebalances;
  d.stats.builds = exch->stats().builds;
  return d;
}

// Index of each id in a set.
std::vector<std::size_t> by_id(const ParticleSet<2>& ps) {
  std::vector<std::size_t> at(ps.total(), ps.total());
  for (std::size_t i = 0; i < ps.total(); ++i) {
    if (ps.id[i] >= at.size()) return {};
    if (at[ps.id[i]] != ps.total()) return {};  // a duplicate
    at[ps.id[i]] = i;
  }
  return at;
}

struct Difference {
  double dx = 0.0, dv = 0.0, drho = 0.0, dt = 0.0;  // dx in dp; dt relative
  // What the pair loop's float rounding may add with a fixed step (0 in the double build):
  // each run's rates are within the per-particle bound A (acceleration) and R (density rate)
  // of verify/pair_rounding.hpp, so the runs' rates differ by up to 2A and 2R; summed over
  // n steps of dt, |dv| <= 2A n dt, |dx| <= 2A dt^2 n (n + 1) / 2, |drho| <= 2R n dt (first
  // order: the feedback of the differences on the rates is neglected, fine while they stay
  // at rounding level). A and R: the largest over the particles at the start and the end.
  double pair_dx = 0.0, pair_drho = 0.0;  // dx in dp
};

Difference compare_to_one_rank(const CaseSetup<2>& setup, const char* what, long rebalance,
                               double width_factor = 1.0, bool expect_migration = true,
                               int axis = 0) {
  const Comm comm = Comm::world();
  Simulation<2> ref = make_simulation<2>(setup, setup.particles);
  for (int s = 0; s < kSteps; ++s) ref.step();
  const Decomposed d = run_decomposed(setup, kSteps, rebalance, width_factor, axis);
  Difference out;
  if (comm.size() > 1) {
    EXPECT_GT(d.stats.images, 0u) << what;
    if (expect_migration)
      EXPECT_GT(d.stats.migrated, 0u) << what << ": no particle crossed a slab face";
  }
  if (rebalance > 0) {
    EXPECT_GE(d.stats.rebalances, static_cast<std::uint64_t>(kSteps / rebalance - 1));
  }
  if (comm.rank() == 0) {
    const ParticleSet<2>& ps = d.gathered;
    const ParticleSet<2>& rp = ref.particles();
    EXPECT_EQ(ps.total(), rp.total()) << what;
    EXPECT_EQ(ps.size(), rp.size()) << what;
    const auto at = by_id(ps), rat = by_id(rp);
    EXPECT_EQ(at.size(), ps.total()) << what << ": an id is missing or duplicated";
    if (at.size() == ps.total() && rat.size() == rp.total() && ps.total() == rp.total()) {
      for (std::size_t id = 0; id < at.size(); ++id) {
        const std::size_t i = at[id], j = rat[id];
        EXPECT_EQ(ps.mass[i], rp.mass[j]);
        EXPECT_EQ(ps.role[i], rp.role[j]);
        EXPECT_EQ(ps.body[i], rp.body[j]);
        Vec<2> dx = ps.pos[i] - rp.pos[j];
        for (int d = 0; d < 2; ++d)  // the nearest image: one run may have wrapped, not the other
          if (setup.params.periodic[static_cast<std::size_t>(d)]) {
            const double L = setup.params.domain_max[d] - setup.params.domain_min[d];
            dx[d] -= L * std::round(dx[d] / L);
          }
        out.dx = std::max(out.dx, dx.norm() / setup.params.dp);
        out.dv = std::max(out.dv, (ps.velocity(i) - rp.velocity(j)).norm());
        out.drho = std::max(out.drho, std::abs(double(ps.rho[i]) - double(rp.rho[j])));
      }
    }
    out.dt = std::abs(d.time - ref.time()) / ref.time();
    if (std::is_same_v<PairReal, float>) {
      double A = 0.0, R = 0.0;
      for (const ParticleSet<2>* q : {&setup.particles, &ref.particles()}) {
        const PairRounding pr = pair_rounding<2>(*q, setup.params);
        A = std::max(A, std::sqrt(2.0) * *std::max_element(pr.acc.begin(), pr.acc.end()));
        R = std::max(R, *std::max_element(pr.drho.begin(), pr.drho.end()));
      }
      const double n = kSteps, dt = ref.dt();
      out.pair_dx = 2.0 * A * dt * dt * n * (n + 1.0) / 2.0 / setup.params.dp;
      out.pair_drho = 2.0 * R * n * dt;
      std::cout << "[ " << what << " ] float pair-rounding bounds: A = " << A << " m/s^2, R = " << R
                << " kg/m^3/s: |dx| <= " << out.pair_dx << " dp, |drho| <= " << out.pair_drho
                << " kg/m^3 (with a fixed step)\n";
    }
    std::cout << "[ " << what << " ] " << comm.size() << " rank(s), " << kSteps
              << " steps: max |dx| = " << out.dx << " dp, max |dv| = " << out.dv
              << " m/s, max |drho| = " << out.drho << " kg/m^3, t = " << d.time << " (one rank "
              << ref.time() << "), images " << d.stats.images << ", migrated " << d.stats.migrated
              << ", rebalances " << d.stats.rebalances << "\n";
  }
  // Every rank gets rank 0's figures.
  out.dx = comm.max(out.dx);
  out.dv = comm.max(out.dv);
  out.drho = comm.max(out.drho);
  out.dt = comm.max(out.dt);
  out.pair_dx = comm.max(out.pair_dx);
  out.pair_drho = comm.max(out.pair_drho);
  return out;
}

// Fixed time step: only the summation order differs, so the states agree to rounding, plus,
// since the pair loop computes in float, the derived Difference::pair_dx / pair_drho (measured
// with the double state: 3e-14 dp, 3e-12 kg/m^3 on 2 and 3 ranks, DBC and mDBC; with the
// float state and double pair terms, 2026-12-05: 0 and 0, 1.2e-15 dp with shifting; with the
// float pair loop: 2.3e-6 dp and 1.8e-4 kg/m^3 (DBC, 2 ranks), 1.6e-6 dp (mDBC), against
// derived bounds of 4.6e-3 dp and 0.095 kg/m^3; a half-width halo gives 0.012-0.022 dp, 2.6-4.7
// times the bound, so the check still catches it). Where such a last-bit
// difference flips the rounding of a stored density (one float step, 6e-5 kg/m^3 near rho0,
// 1.2e-4 above 1024) or velocity (6e-8 of it, moving a particle by ~1e-7 dp over the 300
// steps), the bounds still hold: two float steps, 1e-6 dp. A halo of half the width misses by
// 0.01 dp and 0.2 kg/m^3 and more (AHaloTooNarrowIsCaught).
constexpr double kFixedDx = 1e-6, kFixedRho = 2.5e-4;
// Variable time step: dt (the minimum over ranks of CFL limits that include a maximum over
// pairs) can jump by ~1e-5 relative where a pair at exactly the kernel support is counted on
// one side and not on the other; after such a jump the two runs take other steps. Measured at
// 300 steps (2 and 3 ranks alike): 6.7e-5 dp, 7.7e-4 kg/m^3, 6.9e-5 in t. The bounds sit a
// factor 7-13 above; a halo of half the width misses by 0.01-0.03 dp (AHaloTooNarrowIsCaught).
constexpr double kVarDx = 5e-4, kVarRho = 0.01, kVarT = 5e-4;

std::vector<std::string> fixed_dt() {
  return {"time.dt_fixed=3.5e-5"};
}

TEST(MpiSimulation, DamBreakMatchesOneRankWithAFixedStep) {
  const Difference d = compare_to_one_rank(dam_break(fixed_dt()), "DBC, fixed dt", 25);
  EXPECT_LT(d.dx, kFixedDx + d.pair_dx);
  EXPECT_LT(d.drho, kFixedRho + d.pair_drho);
  EXPECT_EQ(d.dt, 0.0);
}

// The fixed-step dam break with one more edit, against one rank at rounding level.
void expect_fixed_step_match(const std::string& edit, const char* what) {
  std::vector<std::string> sets = fixed_dt();
  sets.push_back(edit);
  const Difference d = compare_to_one_rank(dam_break(sets), what, 25);
  EXPECT_LT(d.dx, kFixedDx + d.pair_dx);
  EXPECT_LT(d.drho, kFixedRho + d.pair_drho);
}

TEST(MpiSimulation, MdbcDamBreakMatchesOneRankWithAFixedStep) {
  expect_fixed_step_match("physics.boundary.model=mdbc", "mDBC, fixed dt");
}

TEST(MpiSimulation, DamBreakMatchesOneRankWithTheVariableStep) {
  const Difference d = compare_to_one_rank(dam_break({}), "DBC, variable dt", 0);
  EXPECT_LT(d.dx, kVarDx);
  EXPECT_LT(d.drho, kVarRho);
  EXPECT_LT(d.dt, kVarT);
}

TEST(MpiSimulation, DamBreakWithRebalancingMatchesOneRank) {
  const Difference d =
      compare_to_one_rank(dam_break({}), "DBC, variable dt, rebalance every 25 steps", 25);
  EXPECT_LT(d.dx, kVarDx);
  EXPECT_LT(d.drho, kVarRho);
  EXPECT_LT(d.dt, kVarT);
}

// The float pair loop's rounding bounds (verify/pair_rounding.hpp) over the run that
// tests/mpi/run_ranks.sh compares across ranks (the dam break at dp 0.0028575 to 0.06 s, one
// rank, every 100 steps and at the end). check_ranks.py quotes A <= 0.5 m/s^2 and R <= 20
// kg/m^3/s to show that the derived first-order bound (A T^2 = 1.8e-3 m) is too loose to check
// anything there, which is why its float bounds are set from measurement; this test keeps
// that statement true.
TEST(MpiSimulation, RoundingBoundsOfTheEndToEndRun) {
  if (!std::is_same_v<PairReal, float>) GTEST_SKIP() << "double pair arithmetic";
  if (Comm::world().rank() != 0) return;
  const CaseSetup<2> setup = dam_break({"time.end=0.06"});
  Simulation<2> sim = make_simulation<2>(setup, setup.particles);
  double A = 0.0, R = 0.0;
  const auto measure = [&]() {
    const PairRounding pr = pair_rounding<2>(sim.particles(), setup.params);
    A = std::max(A, std::sqrt(2.0) * *std::max_element(pr.acc.begin(), pr.acc.end()));
    R = std::max(R, *std::max_element(pr.drho.begin(), pr.drho.end()));
  };
  for (long s = 0; sim.time() < 0.06; ++s) {
    if (s % 100 == 0) measure();
    sim.step();
  }
  measure();
  std::cout << "  end-to-end run to " << sim.time() << " s: A = " << A << " m/s^2, R = " << R
            << " kg/m^3/s\n";
  EXPECT_LT(A, 0.5);
  EXPECT_LT(R, 20.0);
}

// The bounds catch a broken halo: with half the halo width the particles near a slab face
// miss neighbours and the fixed-step comparison fails by orders of magnitude.
TEST(MpiSimulation, AHaloTooNarrowIsCaught) {
  if (Comm::world().size() == 1) GTEST_SKIP() << "one rank: no halo";
  const Difference d = compare_to_one_rank(dam_break(fixed_dt()), "DBC, half halo", 25, 0.5);
  EXPECT_GT(d.dx, 10.0 * kVarDx);
  EXPECT_GT(d.dx, kFixedDx + d.pair_dx);  // outside the fixed-step bound too
}

TEST(MpiSimulation, RunsAreDeterministicForAGivenRankCount) {
  const CaseSetup<2> setup = dam_break({});
  const Decomposed a = run_decomposed(setup, 120, 20), b = run_decomposed(setup, 120, 20);
  if (Comm::world().rank() != 0) return;
  ASSERT_EQ(a.gathered.total(), b.gathered.total());
  for (std::size_t i = 0; i < a.gathered.total(); ++i) {
    ASSERT_EQ(a.gathered.id[i], b.gathered.id[i]);
    ASSERT_EQ(a.gathered.pos[i], b.gathered.pos[i]);
    ASSERT_EQ(a.gathered.velocity(i), b.gathered.velocity(i));
    ASSERT_EQ(a.gathered.rho[i], b.gathered.rho[i]);
  }
  EXPECT_EQ(a.time, b.time);
}

// Shifting on several ranks: the halo images' free-surface normals come from their owners
// (Exchange::refresh_vectors); without them the particles under the surface near a slab face
// would be shifted out through it.
// (Checked: with the exchange of normals switched off the test fails, 5.5e-7 dp on 2 ranks.)
TEST(MpiSimulation, ShiftingDamBreakMatchesOneRankWithAFixedStep) {
  expect_fixed_step_match("physics.shifting={model: fickian}", "DBC + shifting, fixed dt");
}

// Periodic boundaries on several ranks (parallel/halo.hpp: a ring of slabs along a periodic
// slab axis, periodic images carried with the halo on the other axes), fixed step, against one
// rank within the same bounds as the dam break. Checked by hand (2026-12-06): with the sends
// across the periodic faces switched off these three tests miss by 0.27, 0.032 and 0.17 dp on
// 2 ranks (bounds 0.0025-0.0042 dp), and `swell run` of the film (0.05 s) by 0.12 m (slabs
// along x) and 1.8e-4 m (along y) against 8e-8 / 3e-9 m.
//
// cases/film_slope2d.yaml (mDBC bed, periodic along x) with a 2 m/s^2 slope and the fluid
// started at 0.2 m/s along x, so particles cross the periodic faces: `long_x` makes the flume
// 0.12 m long (slabs along x: the ring), otherwise the domain is 0.1 m tall (slabs along y,
// x periodic across them).
CaseSetup<2> film(bool long_x) {
  std::vector<std::string> sets = {"physics.gravity=[2.0, -9.8]", "time.dt_fixed=2e-5"};
  if (long_x) {
    sets.insert(sets.end(), {"domain.max=[0.12, 0.04]", "bodies.0.shape.box.max=[0.12, 0.03]",
                             "bodies.1.shape.box.max=[0.12, 0.02]"});
  } else {
    sets.push_back("domain.max=[0.04, 0.1]");
  }
  CaseSetup<2> s = setup_case<2>(load_case_file(SWELL_SOURCE_DIR "/cases/film_slope2d.yaml", sets));
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    if (s.particles.role[i] == Role::Fluid) {
      s.particles.vel[i][0] = 0.2f;
      s.particles.vel_prev[i][0] = 0.2f;
    }
  return s;
}

TEST(MpiSimulation, PeriodicFilmWithSlabsAlongThePeriodicAxis) {
  const Difference d = compare_to_one_rank(film(true), "periodic film, slabs along x", 25);
  EXPECT_LT(d.dx, kFixedDx + d.pair_dx);
  EXPECT_LT(d.drho, kFixedRho + d.pair_drho);
}

TEST(MpiSimulation, PeriodicFilmWithSlabsAcrossThePeriodicAxis) {
  // The slabs cut the film along y; the flow runs along them (no particle changes slab).
  const Difference d =
      compare_to_one_rank(film(false), "periodic film, slabs along y", 25, 1.0, false, 1);
  EXPECT_LT(d.dx, kFixedDx + d.pair_dx);
  EXPECT_LT(d.drho, kFixedRho + d.pair_drho);
}

// tests/data/mpi_periodic_box2d.yaml: periodic along x (the slab axis) and y, no walls, a
// Taylor-Green vortex (stream function A sin(kx x) sin(ky y), peak speed 0.5 m/s), zero
// gravity, uniform density: particles cross both periodic faces and the slab faces, and the
// corner images come across the ring.
TEST(MpiSimulation, DoublyPeriodicVortexMatchesOneRank) {
  CaseSetup<2> s = setup_case<2>(load_case_file(
      SWELL_SOURCE_DIR "/tests/data/mpi_periodic_box2d.yaml", {"time.dt_fixed=5e-5"}));
  s.params.gravity.setZero();
  const double kx = 2.0 * M_PI / 0.2, ky = 2.0 * M_PI / 0.1, A = 0.5 / ky;
  ParticleSet<2>& ps = s.particles;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double x = ps.pos[i][0], y = ps.pos[i][1];
    ps.vel[i][0] = static_cast<StateReal>(A * ky * std::sin(kx * x) * std::cos(ky * y));
    ps.vel[i][1] = static_cast<StateReal>(-A * kx * std::cos(kx * x) * std::sin(ky * y));
    ps.vel_prev[i] = ps.vel[i];
    ps.rho[i] = ps.rho_prev[i] = static_cast<StateReal>(s.params.rho0);
  }
  const Difference d = compare_to_one_rank(s, "doubly periodic vortex", 25);
  EXPECT_LT(d.dx, kFixedDx + d.pair_dx);
  EXPECT_LT(d.drho, kFixedRho + d.pair_drho);
}

// The set-up distributed over the ranks (each fills its share of the lattice with a margin,
// run/rank_setup.hpp) against the whole case set up on this rank alone: every particle of the
// whole set exactly once over the ranks, each bit for bit the whole set's record (id,
// position, velocity, density and their integrator copies, mass, role, body, and the mDBC
// normal and moving bodies' reference position where enabled), each rank's in the whole set's
// relative order; the same counts, parameters, domain, levels and sort box.
template <int D>
void expect_distributed_setup(const std::string& file, const std::vector<std::string>& sets) {
  const Comm comm = Comm::world();
  const CaseSpec spec = load_case_file(file, sets);
  const CaseSetup<D> whole = setup_case<D>(spec);
  const CaseSetup<D> mine = setup_case<D>(spec, RankSetupReduce(comm));
  EXPECT_EQ(mine.distributed, comm.size() > 1);
  const ParticleSet<D>& w = whole.particles;
  const ParticleSet<D>& m = mine.particles;
  ASSERT_EQ(record_bytes(w), record_bytes(m)) << "the same fields enabled";
  std::vector<std::size_t> at(w.size(), w.size());
  for (std::size_t j = 0; j < w.size(); ++j) at[w.id[j]] = j;
  std::vector<std::uint64_t> seen(w.size(), 0);
  const std::size_t rec = record_bytes(w);
  std::vector<std::byte> a(rec), b(rec);
  std::size_t differ = 0, out_of_order = 0, last = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    ASSERT_LT(m.id[i], w.size()) << "id " << m.id[i];
    const std::size_t j = at[m.id[i]];
    ++seen[m.id[i]];
    pack(m, i, a.data());
    pack(w, j, b.data());
    differ += std::memcmp(a.data(), b.data(), rec) != 0;
    out_of_order += i > 0 && j <= last;
    last = j;
  }
  comm.sum_in_place(seen);
  const auto once = std::count(seen.begin(), seen.end(), std::uint64_t{1});
  EXPECT_EQ(static_cast<std::size_t>(once), w.size()) << "particles held exactly once";
  EXPECT_EQ(comm.sum(static_cast<std::uint64_t>(differ)), 0u) << "records differing";
  EXPECT_EQ(comm.sum(static_cast<std::uint64_t>(out_of_order)), 0u) << "out of the whole order";
  ASSERT_EQ(mine.bodies.size(), whole.bodies.size());
  for (std::size_t k = 0; k < whole.bodies.size(); ++k) {
    EXPECT_EQ(mine.bodies[k].particles, whole.bodies[k].particles) << whole.bodies[k].name;
    EXPECT_EQ(mine.fill[k].particles, whole.fill[k].particles) << whole.bodies[k].name;
    EXPECT_EQ(mine.fill[k].in_region, whole.fill[k].in_region) << whole.bodies[k].name;
  }
  EXPECT_EQ(mine.params.c0, whole.params.c0);
  EXPECT_EQ(mine.params.domain_min, whole.params.domain_min);
  EXPECT_EQ(mine.params.domain_max, whole.params.domain_max);
  EXPECT_EQ(mine.hswl, whole.hswl);
  EXPECT_EQ(mine.floor, whole.floor);
  EXPECT_EQ(mine.warnings, whole.warnings);
  std::cout << "  distributed set-up (" << file.substr(file.rfind('/') + 1) << "): " << m.size()
            << " of " << w.size() << " particles on rank " << comm.rank() << "\n";
}

TEST(MpiSetup, DamBreakSetUpInSharesIsTheWholeCaseSplit) {
  expect_distributed_setup<2>(SWELL_SOURCE_DIR "/cases/dambreak2d.yaml", {"dp=0.0028575"});
}

// Shares across the rows (along y), and a second fluid body that the first one's points cut
// (the fill's `taken` points near the share faces).
TEST(MpiSetup, TallTankWithTwoFluidsSetUpInSharesAlongY) {
  expect_distributed_setup<2>(
      SWELL_SOURCE_DIR "/cases/dambreak2d.yaml",
      {"dp=0.0028575", "bodies.0.shape.box.max=[0.1, 0.6]", "bodies.1.shape.box.max=[0.1, 0.4]",
       "bodies.2={name: oil, kind: fluid, shape: {box: {min: [0, 0.3], max: [0.05, 0.5]}}}",
       "gauges=[]"});
}

// Two equal pools either side of a wall: the shares meet at the wall, whose particles see fluid
// only across the cut (their hydrostatic densities need the fill's margin).
TEST(MpiSetup, WallBetweenTwoPoolsNeedsTheMargin) {
  expect_distributed_setup<2>(
      SWELL_SOURCE_DIR "/cases/dambreak2d.yaml",
      {"dp=0.005", "bodies.0.shape.box.max=[1.02, 0.3]", "bodies.1.shape.box.max=[0.5, 0.2]",
       "bodies.2={name: wall, kind: boundary, walls: outside, layers: 3, "
       "shape: {box: {min: [0.5, 0], max: [0.52, 0.3]}}}",
       "bodies.3={name: pool, kind: fluid, shape: {box: {min: [0.52, 0], max: [1.02, 0.2]}}}",
       "gauges=[]"});
}

// 3D with mDBC walls (normals from the geometry) and a structure.
TEST(MpiSetup, MdbcDamBreak3DSetUpInShares) {
  expect_distributed_setup<3>(SWELL_SOURCE_DIR "/cases/dambreak3d.yaml",
                              {"dp=0.02", "physics.boundary.model=mdbc"});
}

// A moving paddle (reference positions, placed at t = 0) and a damping zone.
TEST(MpiSetup, WaveFlumeSetUpInShares) {
  expect_distributed_setup<2>(SWELL_SOURCE_DIR "/cases/wave_flume_regular2d.yaml", {});
}

}  // namespace
}  // namespace swell::parallel
