#include "verify/tensile.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "bc/dbc.hpp"
#include "solver/time/shifting_hook.hpp"
#include "solver/time/simulation.hpp"
#include "verify/pair_rounding.hpp"

namespace swell::verify {
namespace {

struct Case {
  std::string label;
  double strain;  // rho / rho0 - 1: < 0 tension, > 0 compression
  KernelType kernel;
  bool shifting;
  double perturbation;  // random displacement amplitude / dp
};

struct Run {
  std::vector<double> t, min_dist;  // smallest nearest-neighbour distance / dp over time
  double final_min = 0.0, final_vrms = 0.0;
  // With `rounding_bound`: how far the float pair loop's rounding may move a particle (m):
  // each step's acceleration is within A (the largest per-particle bound of
  // verify/pair_rounding.hpp) of the exact lattice's zero, so |v| <= sum A dt and |x| <= sum
  // |v| dt (first order). 0 in the double build.
  double pair_disp = 0.0;
};

// Smallest distance between two particles (periodic), / dp: O(N) over the 3x3 cells.
double min_distance(const ParticleSet<2>& ps, double L, double dp) {
  const int nc = std::max(1, static_cast<int>(L / (1.5 * dp)));
  const double cs = L / nc;
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(nc * nc));
  auto cell = [&](double x) {
    int i = static_cast<int>(std::floor(x / cs));
    return ((i % nc) + nc) % nc;
  };
  for (std::size_t i = 0; i < ps.size(); ++i)
    cells[cell(ps.pos[i].x()) + nc * cell(ps.pos[i].y())].push_back(static_cast<std::uint32_t>(i));
  double best2 = 1e300;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const int cx = cell(ps.pos[a].x()), cy = cell(ps.pos[a].y());
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        for (std::uint32_t b : cells[((cx + dx + nc) % nc) + nc * ((cy + dy + nc) % nc)]) {
          if (b == a) continue;
          Vec<2> d = ps.pos[a] - ps.pos[b];
          for (int k = 0; k < 2; ++k) d[k] -= L * std::round(d[k] / L);
          best2 = std::min(best2, d.squaredNorm());
        }
  }
  return std::sqrt(best2) / dp;
}

Run run_case(const Case& c, int n, int steps, bool rounding_bound = false) {
  const double dp = 0.01, L = n * dp, rho0 = 1000.0;
  SolverParams p;
  p.dp = dp;
  p.h = std::sqrt(2.0) * dp;
  p.kernel = c.kernel;
  p.gravity.setZero();
  p.c0 = 10.0;
  p.rho0 = rho0;
  p.domain_min = Eigen::Vector3d::Zero();
  p.domain_max = Eigen::Vector3d::Constant(L);
  p.periodic = {true, true, false};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ParticleSet<2> ps;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec<2> x((i + 0.5 + c.perturbation * u(rng)) * dp,
                     (j + 0.5 + c.perturbation * u(rng)) * dp);
      ps.add(x, Vec<2>::Zero(), rho0 * (1.0 + c.strain), rho0 * dp * dp, Role::Fluid, 0);
    }
  Simulation<2>::Hooks hooks;
  if (c.shifting) hooks.push_back(std::make_unique<ShiftingHook<2>>(ShiftingParams{}));
  Simulation<2> sim(p, std::move(ps), make_dbc<2>(), std::move(hooks));
  Run r;
  const int every = std::max(1, steps / 40);
  double v_bound = 0.0;
  for (int s = 0; s <= steps; ++s) {
    if (s % every == 0) {
      r.t.push_back(sim.time());
      r.min_dist.push_back(min_distance(sim.particles(), L, dp));
    }
    if (s >= steps) break;
    double A = 0.0;
    if (rounding_bound && std::is_same_v<PairReal, float>) {
      const PairRounding pr = pair_rounding<2>(sim.particles(), p);
      A = std::sqrt(2.0) * *std::max_element(pr.acc.begin(), pr.acc.end());
    }
    sim.step();
    v_bound += A * sim.dt();
    r.pair_disp += v_bound * sim.dt();
  }
  r.final_min = r.min_dist.back();
  double v2 = 0.0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    v2 += sim.particles().velocity(i).squaredNorm();
  r.final_vrms = std::sqrt(v2 / sim.particles().size());
  return r;
}

}  // namespace

Result run_tensile(const Options& opt) {
  Result r;
  const int n = opt.full ? 48 : 32, steps = opt.full ? 6000 : 2000;
  const double pert = 1e-3;
  const std::vector<Case> cases = {
      {"tension Wendland", -0.01, KernelType::Wendland, false, pert},
      {"tension Wendland + shifting", -0.01, KernelType::Wendland, true, pert},
      {"tension cubic", -0.01, KernelType::Cubic, false, pert},
      {"compression Wendland", 0.01, KernelType::Wendland, false, pert},
      {"compression cubic", 0.01, KernelType::Cubic, false, pert},
  };
  // Equilibrium first: without the seed a lattice under either stress stays exactly a lattice.
  for (double strain : {-0.01, 0.01}) {
    const Run eq = run_case({"", strain, KernelType::Wendland, false, 0.0}, n, 100, true);
    // Exactly a lattice up to round-off: 1e-9 with double pair terms. The float pair loop's
    // derived bound (twice the displacement it allows, reported) is larger than the 1e-3 dp
    // seed of the runs below, so it would check nothing: the 1e-9 is checked in the
    // double-state build (.ci/run) and the float build reports the figure.
    const std::string what = std::string("unperturbed lattice under ") +
                             (strain < 0 ? "tension" : "compression") +
                             ": |min distance / dp - 1| after 100 steps";
    if (std::is_same_v<PairReal, float>) {
      r.figures.push_back(report(what, std::abs(eq.final_min - 1.0)));
      r.figures.push_back(
          report(what + ", float pair loop's derived bound", 2.0 * eq.pair_disp / 0.01));
    } else {
      r.figures.push_back(at_most(what, std::abs(eq.final_min - 1.0), 1e-9));
    }
  }
  Table t{"tensile_min_distance", {"t [s]"}, {}};
  std::vector<Run> runs;
  for (const Case& c : cases) {
    runs.push_back(run_case(c, n, steps));
    t.columns.push_back(c.label);
    r.figures.push_back(
        report(c.label + ": smallest particle distance / dp at the end", runs.back().final_min));
    r.figures.push_back(
        report(c.label + ": RMS velocity at the end", runs.back().final_vrms, "m/s"));
  }
  for (std::size_t k = 0; k < runs[0].t.size(); ++k) {
    std::vector<double> row{runs[0].t[k]};
    for (const Run& run : runs) row.push_back(k < run.min_dist.size() ? run.min_dist[k] : NAN);
    t.rows.push_back(row);
  }
  Plot pl{"tensile_min_distance",
          "Periodic lattice under +-1 % strain: smallest particle distance / dp",
          "tensile_min_distance",
          "t [s]",
          {},
          false,
          false,
          "lines"};
  for (const Case& c : cases) pl.y.push_back(c.label);
  r.plots.push_back(pl);
  r.tables.push_back(t);
  r.notes =
      "A " + std::to_string(n) +
      "^2 lattice (dp = 0.01 m, h = sqrt(2) dp) filling a doubly "
      "periodic box, at rest, with density 0.99 rho0 (tension: P = -" +
      std::to_string(static_cast<int>(std::round(-TaitEos(1000.0, 10.0, 7.0).pressure(990.0)))) +
      " Pa) or 1.01 rho0 (compression), c0 = 10 m/s, artificial viscosity 0.01, Fourtakas "
      "diffusion, symplectic, " +
      std::to_string(steps) +
      " steps; each particle displaced by up to 1e-3 dp at random (seed 11). Without the seed "
      "the lattice is an equilibrium (checked to 1e-9 plus the float pair loop's derived rounding "
      "bound). With it, the smallest distance between "
      "two particles over time shows whether the order survives: under tension the particles "
      "clump (the tensile instability), Fickian shifting (A = 2) is the correction shown; under "
      "compression the cubic spline's pairing is the classic failure.";
  return r;
}

}  // namespace swell::verify
