// A tank at rest stays at rest: hydrostatic initial density, DBC walls, gravity. After
// settling, the pressure at depth d follows rho0 g d and no particle leaves the tank.
#include <gtest/gtest.h>

#include <cmath>

#include "case/reader.hpp"
#include "run/run.hpp"
#include "solver/diagnostics.hpp"

namespace swell {
namespace {

constexpr double kWidth = 0.4, kDepth = 0.2, kG = 9.81, kRho0 = 1000.0;

CaseSpec tank_case(int dim, double dp, double t_end) {
  std::string text;
  if (dim == 2) {
    text = "dim: 2\ndp: " + std::to_string(dp) + "\ntime: {end: " + std::to_string(t_end) +
           "}\nbodies:\n"
           "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.4, 0.3]}}, layers: "
           "3}\n"
           "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.4, 0.2]}}}\n";
  } else {
    text = "dim: 3\ndp: " + std::to_string(dp) + "\ntime: {end: " + std::to_string(t_end) +
           "}\nbodies:\n"
           "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0, 0], max: [0.4, 0.2, 0.3]}}, "
           "layers: 2, open: [zmax]}\n"
           "  - {name: water, kind: fluid, shape: {box: {min: [0, 0, 0], max: [0.4, 0.2, 0.2]}}}\n";
  }
  return parse_case_text(text, "hydrostatic_tank.yaml");
}

// Mean fluid pressure in horizontal bands, compared with rho0 g d at the band's mean depth.
template <int D>
void check_hydrostatic(double dp, double t_end, double tol) {
  const CaseSpec spec = tank_case(D, dp, t_end);
  CaseSetup<D> setup = setup_case<D>(spec);
  Simulation<D> sim = make_simulation<D>(setup, std::move(setup.particles));

  // Starts at rest: after 50 steps the fastest particle moves far slower than sqrt(g H).
  for (int s = 0; s < 50; ++s) sim.step();
  const double v_scale = std::sqrt(kG * kDepth);
  EXPECT_LT(fluid_totals(sim.particles()).max_speed, 0.02 * v_scale)
      << "tank does not start at rest";

  while (sim.time() < t_end) sim.step();
  const auto& ps = sim.particles();
  const auto& p = sim.pressure();
  EXPECT_EQ(sim.excluded().total(), 0u);

  const int up = D - 1;
  const int nbands = 8;
  std::vector<double> sum_p(nbands, 0.0), sum_d(nbands, 0.0);
  std::vector<int> count(nbands, 0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.role[i] != Role::Fluid) continue;
    for (int d = 0; d < D; ++d) {
      const double hi = d == 0 ? kWidth : (d == up ? 0.3 : 0.2);
      EXPECT_GT(ps.pos[i][d], 0.0) << "particle left the tank";
      EXPECT_LT(ps.pos[i][d], hi) << "particle left the tank";
    }
    const double depth = kDepth - ps.pos[i][up];
    const int b = std::clamp(static_cast<int>(depth / kDepth * nbands), 0, nbands - 1);
    sum_p[b] += p[i];
    sum_d[b] += depth;
    ++count[b];
  }
  const double p_bottom = kRho0 * kG * kDepth;
  double worst = 0.0;
  // Skip the top band (free surface: kernel truncation lowers the density there).
  for (int b = 1; b < nbands; ++b) {
    ASSERT_GT(count[b], 0);
    const double depth = sum_d[b] / count[b];
    const double p_mean = sum_p[b] / count[b];
    const double err = (p_mean - kRho0 * kG * depth) / p_bottom;
    std::cout << "  " << D << "D depth " << depth << " m: p = " << p_mean
              << " Pa, rho0 g d = " << kRho0 * kG * depth << " Pa, error " << 100 * err
              << " % of rho0 g H\n";
    worst = std::max(worst, std::abs(err));
  }
  EXPECT_LT(worst, tol);
  const auto tot = fluid_totals(ps);
  EXPECT_LT(tot.max_speed, 0.05 * v_scale) << "tank has not settled";
}

// Tolerance: 3% of the bottom pressure rho0 g H. A WCSPH tank with DBC walls and the default
// Fourtakas diffusion settles to within about 1% here; errors from a wrong EoS, a missing
// hydrostatic initialisation or a sign error in gravity are tens of percent.
TEST(Hydrostatic, Tank2DPressureFollowsDepth) {
  check_hydrostatic<2>(0.01, 1.0, 0.03);
}
TEST(Hydrostatic, Tank3DPressureFollowsDepth) {
  check_hydrostatic<3>(0.02, 0.6, 0.03);
}

}  // namespace
}  // namespace swell
