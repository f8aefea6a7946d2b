#include "verify/noh.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "verify/sod.hpp"

namespace swell::verify {

using compressible::GasParams;
using compressible::GasSolver;

namespace {
constexpr double kGamma = 5.0 / 3.0, kTEnd = 0.6;
// Exact planar Noh solution for a cold stream of unit density and speed: the shock speed is
// (gamma - 1) / 2 = 1/3, the post-shock density (gamma + 1) / (gamma - 1) = 4, all kinetic
// energy turned into heat: u = 1/2, p = (gamma - 1) rho u = 4/3.
constexpr double kShockSpeed = (kGamma - 1.0) / 2.0;
constexpr double kRhoPost = (kGamma + 1.0) / (kGamma - 1.0), kUPost = 0.5;
constexpr double kWindow = 0.35;  // errors over 0 < x < 0.35: wall, shock (0.2), inflow ahead

struct NohLevel {
  double l1_rho = 0, l1_v = 0, l1_u = 0;
  double l1_rho_debiased = 0;  // with rho / (1 + beta), beta the lattice's summation bias
  double plateau_rho = 0;      // mean rho over 0.05 < x < 0.15 (behind the shock, off the wall)
  double wall_rho = 0;         // rho of the particle next to the wall
  double wall_u = 0;           // its u
  double shock_x = 0;          // where rho first falls below (4 + 1) / 2, from the wall out
  double overshoot = 0;        // largest rho above 4 behind the shock, relative to the jump 3
  int steps = 0;
  double secs = 0;
};

NohLevel measure_noh(const GasSolver<1>& gas, double bias) {
  NohLevel L;
  const double xs = kShockSpeed * gas.time();
  std::size_t wall = 0;
  double ps = 0.0;
  int np = 0;
  L.shock_x = std::numeric_limits<double>::quiet_NaN();
  double first_below = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < gas.size(); ++a) {
    const double x = gas.pos[a][0];
    if (x < gas.pos[wall][0]) wall = a;
    if (x > 0.05 && x < 0.15) ps += gas.rho[a], ++np;
    if (x < xs) L.overshoot = std::max(L.overshoot, (gas.rho[a] - kRhoPost) / (kRhoPost - 1.0));
    if (gas.rho[a] < 0.5 * (kRhoPost + 1.0) && x > 0.05) first_below = std::min(first_below, x);
    if (x >= kWindow) continue;
    const bool post = x < xs;
    const double vol = gas.mass[a] / gas.rho[a];
    L.l1_rho += vol * std::abs(gas.rho[a] - (post ? kRhoPost : 1.0));
    L.l1_rho_debiased += vol * std::abs(gas.rho[a] / bias - (post ? kRhoPost : 1.0));
    L.l1_v += vol * std::abs(gas.vel[a][0] - (post ? 0.0 : -1.0));
    L.l1_u += vol * std::abs(gas.u[a] - (post ? kUPost : 0.0));
  }
  L.plateau_rho = np ? ps / np : 0.0;
  L.wall_rho = gas.rho[wall];
  L.wall_u = gas.u[wall];
  if (std::isfinite(first_below)) L.shock_x = first_below;
  return L;
}

double slope(const std::vector<double>& n, const std::vector<double>& err) {
  return -fitted_order(n, err);  // err ~ n^-order
}
}  // namespace

std::unique_ptr<GasSolver<1>> make_noh_1d(int n, double u0) {
  using V = Vec<1>;
  GasParams prm;
  prm.gamma = kGamma;
  auto gas = std::make_unique<GasSolver<1>>(prm, V(0.0), V(3.0), std::array<bool, 1>{true});
  const double dx = 1.0 / n;
  for (int i = 0; i < n; ++i) gas->add(V((i + 0.5) * dx), V(-1.0), dx, u0, prm.eta * dx);
  gas->initialise();
  return gas;
}

Result run_noh(const Options& opt) {
  Result res;
  const std::vector<int> levels =
      opt.full ? std::vector<int>{200, 400, 800, 1600} : std::vector<int>{50, 100, 200};
  Table t{"noh_errors",
          {"n", "L1 rho", "lattice bias", "L1 rho de-biased", "L1 v", "L1 u", "plateau rho",
           "wall rho", "wall u", "shock x - t/3 [dx]", "overshoot rho", "steps", "run time [s]"},
          {}};
  Table profile{"noh_profile", {"x", "rho", "v", "u", "p"}, {}};
  std::vector<double> ns, er, erraw, ev, eu;
  double worst_plateau = 0.0, worst_shock = 0.0, worst_over = 0.0;  // shock: in dx
  for (const int n : levels) {
    const auto t0 = std::chrono::steady_clock::now();
    auto gas = make_noh_1d(n);
    // The summation density's bias on the uniform stream (+0.18 % for the cubic spline at
    // eta = 1.2, as in the Sod tube): a floor under the raw L1 of rho, taken out before the
    // order is fitted (the raw order is reported).
    const double beta = gas->rho[static_cast<std::size_t>(n / 2)] - 1.0;
    NohLevel L;
    L.steps = run_gas(*gas, kTEnd, 0.0);
    L.secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const NohLevel m = measure_noh(*gas, 1.0 + beta);
    const double shock_dx = (m.shock_x - kShockSpeed * kTEnd) * n;
    t.rows.push_back({double(n), m.l1_rho, beta, m.l1_rho_debiased, m.l1_v, m.l1_u, m.plateau_rho,
                      m.wall_rho, m.wall_u, shock_dx, m.overshoot, double(L.steps), L.secs});
    ns.push_back(n), er.push_back(m.l1_rho_debiased), erraw.push_back(m.l1_rho),
        ev.push_back(m.l1_v), eu.push_back(m.l1_u);
    worst_plateau = std::max(worst_plateau, std::abs(m.plateau_rho / kRhoPost - 1.0));
    worst_shock = std::max(worst_shock, std::abs(shock_dx));
    worst_over = std::max(worst_over, m.overshoot);
    const std::string tag = ", n = " + std::to_string(n);
    res.figures.push_back(report("L1 error of rho" + tag, m.l1_rho));
    res.figures.push_back(report("L1 error of rho / (1 + bias)" + tag, m.l1_rho_debiased));
    res.figures.push_back(report("wall density / 4 (wall heating)" + tag, m.wall_rho / kRhoPost));
    res.figures.push_back(report("wall internal energy / 0.5" + tag, m.wall_u / kUPost));
    if (n == levels.back())
      for (std::size_t a = 0; a < gas->size(); ++a)
        if (gas->pos[a][0] < 0.45)
          profile.rows.push_back(
              {gas->pos[a][0], gas->rho[a], gas->vel[a][0], gas->u[a], gas->pressure[a]});
  }
  std::sort(profile.rows.begin(), profile.rows.end());
  // Bounds: the shock is captured over a few h, so L1 falls like 1/n (order 1 at a shock);
  // the wall-heating dip is a fixed number of particles wide, so its L1 share falls like 1/n
  // too. 0.7 leaves room for the pre-asymptotic levels.
  res.figures.push_back(report("fitted order of L1(rho) (raw)", slope(ns, erraw)));
  res.figures.push_back(at_least("fitted order of L1(rho / (1 + bias))", slope(ns, er), 0.7));
  res.figures.push_back(at_least("fitted order of L1(v)", slope(ns, ev), 0.7));
  res.figures.push_back(at_least("fitted order of L1(u)", slope(ns, eu), 0.7));
  // The jump conditions: the plateau density and the shock position (speed 1/3) follow from
  // mass and momentum conservation alone, so they hold at every resolution.
  res.figures.push_back(
      at_most("largest |plateau rho / 4 - 1| (0.05 < x < 0.15)", worst_plateau, 0.02));
  // The shock is spread over ~2h = 2.4 dx; its half-height point must sit within 2 dx of t/3.
  res.figures.push_back(at_most("largest |shock position - t/3| / dx", worst_shock, 2.0));
  res.figures.push_back(
      at_most("largest density overshoot behind the shock / jump", worst_over, 0.05));
  res.tables.push_back(t);
  res.tables.push_back(profile);
  res.plots.push_back({"noh_errors",
                       "Noh: L1 errors at t = 0.6 against particle number",
                       "noh_errors",
                       "n",
                       {"L1 rho", "L1 rho de-biased", "L1 v", "L1 u"},
                       true,
                       true,
                       "lines+points"});
  res.plots.push_back({"noh_profile",
                       "Noh: density at t = 0.6 (finest level); exact 4 behind x = 0.2, 1 ahead",
                       "noh_profile",
                       "x",
                       {"rho"},
                       false,
                       false,
                       "points"});
  res.notes =
      "Planar Noh problem (gamma = 5/3): equal-mass particles on [0, 1] with v = -1 and "
      "u = 1e-6 hit a mirror wall at x = 0; at t = 0.6 the exact shock is at x = 0.2 with "
      "rho = 4, v = 0, u = 1/2 behind it. Errors over 0 < x < 0.35. Wall heating (the first "
      "particles at the wall over-heated by the artificial viscosity, their density too low) is "
      "reported per level, not judged: it is the known defect of SPH (and of most shock-capturing "
      "schemes) on this problem and needs an artificial conductivity term, which the compressible "
      "path does not have.";
  return res;
}

}  // namespace swell::verify
