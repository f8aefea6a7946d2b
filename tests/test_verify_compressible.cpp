// The fast forms of the compressible-path verifications (verify/sod, verify/energy): every
// bound must hold; every figure is printed. Plus the conservation property they rest on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "verify/energy.hpp"
#include "verify/noh.hpp"
#include "verify/sod.hpp"

namespace swell::verify {
namespace {

void print(const char* name, const Result& r) {
  for (const auto& f : r.figures)
    std::printf("%s: %-62s %14.6g %s (bound %g)\n", name, f.name.c_str(), f.value,
                f.pass() ? "pass" : "FAIL", f.bound);
}

TEST(VerifyCompressible, Sod) {
  const Result r = run_sod(Options{});
  print("sod", r);
  EXPECT_TRUE(r.passed());
  EXPECT_FALSE(r.tables.empty());
}

TEST(VerifyCompressible, Energy) {
  const Result r = run_energy(Options{});
  print("energy", r);
  EXPECT_TRUE(r.passed());
}

TEST(VerifyCompressible, Noh) {
  const Result r = run_noh(Options{});
  print("noh", r);
  EXPECT_TRUE(r.passed());
}

// Noh's stream is uniform and cold: mass is conserved exactly, and at t = 0 the wall's
// ghosts are the only source of compression. After the run every particle that passed the
// shock is at rest to within the shock's smearing, and the total energy sum m (v^2/2 + u) is
// the initial kinetic energy n m / 2 to the integrator's error: the wall (a mirror plane)
// does no work on a gas it stops.
TEST(VerifyCompressible, NohStopsTheStreamWithoutLosingEnergy) {
  auto gas = make_noh_1d(100);
  const double e0 = gas->total_energy();
  EXPECT_NEAR(e0, 0.5 + 1e-6, 1e-12);  // unit mass at v = -1, plus the cold u
  run_gas(*gas, 0.6, 0.0);
  EXPECT_NEAR(gas->total_energy() / e0, 1.0, 1e-4);
  int behind = 0;
  for (std::size_t a = 0; a < gas->size(); ++a)
    if (gas->pos[a][0] < 0.15) {
      ++behind;
      EXPECT_LT(std::abs(gas->vel[a][0]), 0.05) << "particle " << a << " at " << gas->pos[a][0];
    }
  // About 0.15 * 4 / dx = 60 particles lie behind x = 0.15 (compressed 4:1).
  EXPECT_NEAR(behind, 60, 3);
}

// Mean pressure on the plateau between the fan's tail and the contact (0 < x < 0.15 at
// t = 0.2), where the exact solution is p* = 0.30313 (Toro 2009, Test 1).
template <class Gas>
double plateau_pressure(const Gas& gas) {
  double s = 0.0;
  int n = 0;
  for (std::size_t a = 0; a < gas.size(); ++a)
    if (gas.pos[a][0] > 0.0 && gas.pos[a][0] < 0.15) s += gas.pressure[a], ++n;
  return s / n;
}
constexpr double kPStar = 0.30313;

// The 3D slab (run in full only by `swell verify sod --full`), at one coarse level: the
// plateau pressure and a one-dimensional flow.
TEST(VerifyCompressible, Sod3DSlabPlateauAndTransverseVelocity) {
  auto gas = make_sod_slab_3d(32, 8, 1.8);
  run_gas(*gas, 0.2, 0.0);
  double v2 = 0.0;
  for (std::size_t a = 0; a < gas->size(); ++a)
    v2 += gas->vel[a][1] * gas->vel[a][1] + gas->vel[a][2] * gas->vel[a][2];
  const double p = plateau_pressure(*gas), vperp = std::sqrt(v2 / gas->size()) / 0.92745;
  std::printf("3D slab n_left 32: plateau p %.5f (p* %.5f), RMS v_perp / v* %.2e\n", p, kPStar,
              vperp);
  EXPECT_NEAR(p / kPStar, 1.0, 0.02);
  EXPECT_LT(vperp, 0.05);
}

// Why the slabs raise eta: at the 1D tube's eta = 1.2 the lattice stretched along x by the fan
// is no longer resolved and the plateau pressure is biased high by several per cent (8 %
// measured) at every resolution; eta = 1.5 removes the bias.
TEST(VerifyCompressible, Sod2DSlabNeedsTheStretchedDirectionResolved) {
  auto coarse_eta = make_sod_slab(100, 16, 1.2);
  run_gas(*coarse_eta, 0.2, 0.0);
  auto raised = make_sod_slab(100, 16, 1.5);
  run_gas(*raised, 0.2, 0.0);
  const double p12 = plateau_pressure(*coarse_eta) / kPStar,
               p15 = plateau_pressure(*raised) / kPStar;
  std::printf("2D slab n_left 100: plateau p / p* %.4f (eta 1.2), %.4f (eta 1.5)\n", p12, p15);
  EXPECT_GT(p12, 1.05);
  EXPECT_NEAR(p15, 1.0, 0.02);
}

// The spatial discretisation conserves energy: sum m (v.a + du/dt) = 0 up to round-off, on a
// Sod tube part-way through the run (shock, contact and fan present, viscosity active).
TEST(VerifyCompressible, SpatialEnergyRateIsRoundOff) {
  auto gas = make_sod_1d(200);
  run_gas(*gas, 0.1, 0.0);
  gas->initialise();   // forces with the current v and u (a step evaluates them at the predicted
                       // ones)
  double scale = 0.0;  // sum of |terms|: the size round-off is relative to
  for (std::size_t a = 0; a < gas->size(); ++a)
    scale += gas->mass[a] * (std::abs(gas->vel[a].dot(gas->acc[a])) + std::abs(gas->du[a]));
  std::printf("energy rate %.3e, scale %.3e\n", gas->energy_rate(), scale);
  EXPECT_LT(std::abs(gas->energy_rate()), 1e-12 * scale);
}

// A uniform gas at rest stays at rest: summation density recovers rho on the lattice with
// the mirror walls, and the pressure forces cancel.
TEST(VerifyCompressible, UniformGasAtRest) {
  using V = Vec<1>;
  compressible::GasSolver<1> gas({}, V(-0.5), V(0.5), {true});
  const int n = 100;
  for (int i = 0; i < n; ++i) gas.add(V(-0.5 + (i + 0.5) / n), V(0.0), 1.0 / n, 2.5, 1.2 / n);
  gas.initialise();
  for (std::size_t a = 0; a < gas.size(); ++a) {
    // The cubic spline's summation on a uniform 1D lattice is exact to ~1e-3 for eta = 1.2
    // (a partition-of-unity error); the Newton solve itself converges to 1e-10.
    EXPECT_NEAR(gas.rho[a], 1.0, 2e-3);
    EXPECT_NEAR(gas.acc[a][0], 0.0, 1e-10);
    EXPECT_NEAR(gas.h[a], 1.2 / n / gas.rho[a], 1e-9 / n);
  }
}

}  // namespace
}  // namespace swell::verify
