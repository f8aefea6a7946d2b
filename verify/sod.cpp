#include "verify/sod.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "solver/compressible/riemann.hpp"

namespace swell::verify {

using compressible::GasParams;
using compressible::GasSolver;
using compressible::GasState;
using compressible::RiemannSolver;

namespace {
constexpr double kGamma = 1.4, kTEnd = 0.2;
const GasState kLeft{1.0, 0.0, 1.0}, kRight{0.125, 0.0, 0.1};
constexpr double kWindow = 0.4;  // L1 errors over |x| < 0.4: every wave, away from the walls

struct Errors {
  double rho = 0, v = 0, p = 0, u = 0;
  double overshoot_v = 0, overshoot_rho = 0;
};

// bias: the summation density's relative bias on the initial lattice (1 + beta); rho and p
// are divided by it before they are compared (1 for the raw errors).
template <class Gas>
Errors measure(const Gas& gas, const RiemannSolver& rs, Table* profile, double bias = 1.0) {
  constexpr int D = Gas::V::RowsAtCompileTime;
  Errors e;
  const auto& s = rs.star();
  for (std::size_t a = 0; a < gas.size(); ++a) {
    const double x = gas.pos[a][0];
    const GasState q = rs.at(x, 0.0, gas.time());
    const double ue = gas.eos().internal_energy(q.rho, q.p);
    // Overshoot past the post-shock plateau (between contact and shock), relative to the jump.
    if (x > 0.0 && x < 0.45) {
      e.overshoot_v = std::max(e.overshoot_v, (gas.vel[a][0] - s.u) / s.u);
      e.overshoot_rho =
          std::max(e.overshoot_rho, x > s.u * gas.time() + 0.02
                                        ? (gas.rho[a] - s.rho_right) / (s.rho_right - kRight.rho)
                                        : 0.0);
    }
    if (profile && (D == 1 || a % 4 == 0))
      profile->rows.push_back(
          {x, gas.rho[a], gas.vel[a][0], gas.pressure[a], gas.u[a], q.rho, q.u, q.p, ue});
    if (std::abs(x) >= kWindow) continue;
    // Volume-weighted: sum V_a |q_a - q(x_a)| approximates the integral of |error| dx (per unit
    // cross-section in 2D).
    double vol = gas.mass[a] / gas.rho[a];
    e.rho += vol * std::abs(gas.rho[a] / bias - q.rho);
    e.v += vol * std::abs(gas.vel[a][0] - q.u);
    e.p += vol * std::abs(gas.pressure[a] / bias - q.p);
    e.u += vol * std::abs(gas.u[a] - ue);
  }
  return e;
}

double fit_order(const std::vector<double>& n, const std::vector<double>& err) {
  return -fitted_order(n, err);  // err ~ n^-order
}
}  // namespace

std::unique_ptr<GasSolver<1>> make_sod_1d(int n_left) {
  using V = Vec<1>;
  GasParams prm;
  prm.gamma = kGamma;
  auto gas = std::make_unique<GasSolver<1>>(prm, V(-0.5), V(0.5), std::array<bool, 1>{true});
  const double dxl = 0.5 / n_left, m = kLeft.rho * dxl;
  const int n_right = n_left / 8;
  const double dxr = 0.5 / n_right;
  const compressible::IdealGas eos{kGamma};
  for (int i = 0; i < n_left; ++i)
    gas->add(V(-0.5 + (i + 0.5) * dxl), V(0.0), m, eos.internal_energy(kLeft.rho, kLeft.p),
             prm.eta * dxl);
  for (int i = 0; i < n_right; ++i)
    gas->add(V((i + 0.5) * dxr), V(0.0), m, eos.internal_energy(kRight.rho, kRight.p),
             prm.eta * dxr);
  gas->initialise();
  return gas;
}

std::unique_ptr<GasSolver<2>> make_sod_slab(int n_left, int rows_left, double eta) {
  using V = Vec<2>;
  GasParams prm;
  prm.gamma = kGamma;
  prm.eta = eta;
  const double d = 0.5 / n_left, W = rows_left * d;
  auto gas =
      std::make_unique<GasSolver<2>>(prm, V(-0.5, 0.0), V(0.5, W), std::array<bool, 2>{true, true});
  const compressible::IdealGas eos{kGamma};
  for (int j = 0; j < rows_left; ++j)
    for (int i = 0; i < n_left; ++i)
      gas->add(V(-0.5 + (i + 0.5) * d, (j + 0.5) * d), V::Zero(), kLeft.rho * d * d,
               eos.internal_energy(kLeft.rho, kLeft.p), prm.eta * d);
  const double dr = 2.0 * d;
  for (int j = 0; j < rows_left / 2; ++j)
    for (int i = 0; i < n_left / 2; ++i)
      gas->add(V((i + 0.5) * dr, (j + 0.5) * dr), V::Zero(), kRight.rho * dr * dr,
               eos.internal_energy(kRight.rho, kRight.p), prm.eta * dr);
  gas->initialise();
  return gas;
}

std::unique_ptr<GasSolver3W> make_sod_slab_3d(int n_left, int rows_left, double eta) {
  using V = Vec<3>;
  GasParams prm;
  prm.gamma = kGamma;
  prm.eta = eta;
  const double d = 0.5 / n_left, W = rows_left * d;
  auto gas = std::make_unique<GasSolver3W>(prm, V(-0.5, 0.0, 0.0), V(0.5, W, W),
                                           std::array<bool, 3>{true, true, true});
  const compressible::IdealGas eos{kGamma};
  // Spacing ratio 2 = 8^(1/3): equal masses on both sides, as in the 1D tube.
  for (int k = 0; k < rows_left; ++k)
    for (int j = 0; j < rows_left; ++j)
      for (int i = 0; i < n_left; ++i)
        gas->add(V(-0.5 + (i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d), V::Zero(),
                 kLeft.rho * d * d * d, eos.internal_energy(kLeft.rho, kLeft.p), prm.eta * d);
  const double dr = 2.0 * d;
  for (int k = 0; k < rows_left / 2; ++k)
    for (int j = 0; j < rows_left / 2; ++j)
      for (int i = 0; i < n_left / 2; ++i)
        gas->add(V((i + 0.5) * dr, (j + 0.5) * dr, (k + 0.5) * dr), V::Zero(),
                 kRight.rho * dr * dr * dr, eos.internal_energy(kRight.rho, kRight.p),
                 prm.eta * dr);
  gas->initialise();
  return gas;
}

template <class Gas>
int run_gas(Gas& gas, double t_end, double dt_fixed) {
  int steps = 0;
  while (gas.time() < t_end * (1.0 - 1e-12)) {
    double dt = dt_fixed > 0.0 ? dt_fixed : gas.dt_cfl();
    dt = std::min(dt, t_end - gas.time());
    gas.step(dt);
    ++steps;
  }
  return steps;
}
template int run_gas(GasSolver<1>&, double, double);
template int run_gas(GasSolver<2>&, double, double);
template int run_gas(GasSolver3W&, double, double);

namespace {
// One slab level: L1 errors per unit cross-section, the transverse velocity, and the mean
// pressure on the plateau between the fan's tail and the contact (0 < x < 0.15 at t = 0.2)
// against p*.
struct SlabLevel {
  Errors e;
  double vperp = 0, plateau_p = 0, secs = 0;
  int steps = 0;
  std::size_t n = 0;
};
template <class Gas>
SlabLevel run_slab(Gas& gas, const RiemannSolver& rs, double cross_section,
                   std::chrono::steady_clock::time_point t0) {
  constexpr int D = Gas::V::RowsAtCompileTime;
  SlabLevel L;
  L.steps = run_gas(gas, kTEnd, 0.0);
  L.secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  L.n = gas.size();
  L.e = measure(gas, rs, nullptr);
  for (double* q : {&L.e.rho, &L.e.v, &L.e.p, &L.e.u}) *q /= cross_section;
  double v2 = 0.0, ps = 0.0;
  int np = 0;
  for (std::size_t a = 0; a < gas.size(); ++a) {
    for (int d = 1; d < D; ++d) v2 += gas.vel[a][d] * gas.vel[a][d];
    const double x = gas.pos[a][0];
    if (x > 0.0 && x < 0.15) ps += gas.pressure[a], ++np;
  }
  L.vperp = std::sqrt(v2 / gas.size()) / rs.star().u;
  L.plateau_p = np ? ps / np : 0.0;
  return L;
}
}  // namespace

Result run_sod(const Options& opt) {
  Result res;
  const RiemannSolver rs(kLeft, kRight, kGamma);
  std::vector<int> levels =
      opt.full ? std::vector<int>{400, 800, 1600, 3200, 6400} : std::vector<int>{200, 400, 800};
  Table errors{"sod_errors",
               {"n_left", "L1 rho", "L1 v", "L1 p", "L1 u", "lattice bias", "L1 rho de-biased",
                "L1 p de-biased", "overshoot v", "overshoot rho", "steps", "run time [s]"},
               {}};
  Table profile{
      "sod_profile", {"x", "rho", "v", "p", "u", "rho exact", "v exact", "p exact", "u exact"}, {}};
  std::vector<double> ns, er, ev, ep, eu, erb, epb;
  double worst_v = 0, worst_rho = 0;
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const auto t0 = std::chrono::steady_clock::now();
    auto gas = make_sod_1d(levels[l]);
    // The summation density of the initial left lattice (a particle a quarter in): at fixed
    // eta every uniform region carries the same relative bias (Quinlan et al. 2006's
    // discretisation term, which depends on dx/h only), and rho and p with it.
    const double bias = gas->rho[std::size_t(levels[l] / 4)] / kLeft.rho;
    const int steps = run_gas(*gas, kTEnd, 0.0);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Errors e = measure(*gas, rs, l + 1 == levels.size() ? &profile : nullptr);
    const Errors eb = measure(*gas, rs, nullptr, bias);
    errors.rows.push_back({double(levels[l]), e.rho, e.v, e.p, e.u, bias - 1.0, eb.rho, eb.p,
                           e.overshoot_v, e.overshoot_rho, double(steps), secs});
    ns.push_back(levels[l]), er.push_back(e.rho), ev.push_back(e.v), ep.push_back(e.p),
        eu.push_back(e.u), erb.push_back(eb.rho), epb.push_back(eb.p);
    worst_v = std::max(worst_v, e.overshoot_v);
    worst_rho = std::max(worst_rho, e.overshoot_rho);
    const std::string n = ", n_left = " + std::to_string(levels[l]);
    res.figures.push_back(report("L1 error of rho" + n, e.rho));
    res.figures.push_back(report("L1 error of v" + n, e.v));
    res.figures.push_back(report("L1 error of p" + n, e.p));
    res.figures.push_back(report("L1 error of u" + n, e.u));
    res.figures.push_back(report("summation-density bias of the initial lattice" + n, bias - 1.0));
    res.figures.push_back(report("L1 error of rho / (1 + bias)" + n, eb.rho));
    res.figures.push_back(report("L1 error of p / (1 + bias)" + n, eb.p));
    res.figures.push_back(report("run time" + n, secs, "s"));
  }
  // Orders: with a shock, a contact and the kinks of a rarefaction the L1 error of any
  // consistent scheme converges at most at first order; the contact, smeared over a width
  // that grows like sqrt(h) under a first-order dissipation, gives rho and u order ~1/2 to 1.
  // Bounds: 0.6 for v and p (smooth across the contact), 0.4 for rho and u.
  // rho and p are judged after the lattice bias is divided out: the raw errors level off at
  // bias x the integral of rho (or p) over the window (9e-4 at eta = 1.2, measured with
  // --full), a floor no resolution removes at fixed eta; their raw orders are reported.
  res.figures.push_back(report("fitted L1 order of rho (raw)", fit_order(ns, er)));
  res.figures.push_back(report("fitted L1 order of p (raw)", fit_order(ns, ep)));
  res.figures.push_back(at_least("fitted L1 order of rho / (1 + bias)", fit_order(ns, erb), 0.4));
  res.figures.push_back(at_least("fitted L1 order of v", fit_order(ns, ev), 0.6));
  res.figures.push_back(at_least("fitted L1 order of p / (1 + bias)", fit_order(ns, epb), 0.6));
  res.figures.push_back(at_least("fitted L1 order of u", fit_order(ns, eu), 0.4));
  // The finest level must also be accurate in absolute terms: 1 % of the jumps' L1 content
  // is about a 2-smoothing-length error band at each wave.
  res.figures.push_back(at_most("L1 error of rho, finest", er.back(), 0.01));
  // Monaghan's v_sig viscosity with beta = 2 damps post-shock ringing to a few per cent.
  res.figures.push_back(at_most("largest post-shock overshoot of v / v*", worst_v, 0.05));
  res.figures.push_back(at_most("largest post-shock overshoot of rho / jump", worst_rho, 0.10));
  // The slabs: the same tube on 2D and 3D lattices between mirror walls, so the solution must
  // stay one-dimensional; L1 errors per unit cross-section. A lattice crossing the fan is
  // stretched along x only, by rho_L / rho*_L = 2.35 at its tail, while h = eta (m/rho)^(1/D)
  // grows by 2.35^(1/D): the x spacing over h grows by 2.35^(1 - 1/D). At eta = 1.2 that is
  // 1.27 (2D) and 1.47 (3D): the kernel then samples one neighbour column per side and the
  // plateau pressure comes out 8 % (2D) and 29 % (3D) high at every resolution (measured).
  // eta >= 2.35^(1 - 1/D) keeps the x spacing within h: 1.5 in 2D (cubic spline, ~28
  // neighbours); 1.8 in 3D, where the cubic spline pairs (transverse velocity 3.5 % of v* at
  // n_left 50, measured) and the Wendland C2 kernel, which does not, is used.
  Table slab{"sod_slab_errors",
             {"D", "n_left", "rows", "particles", "eta", "L1 rho", "L1 v", "L1 p", "L1 u",
              "plateau p / p*", "RMS v_perp / v*", "overshoot v", "steps", "run time [s]"},
             {}};
  struct SlabSpec {
    int dim, n_left, rows;
  };
  std::vector<SlabSpec> specs =
      opt.full ? std::vector<SlabSpec>{{2, 100, 16}, {2, 200, 16}, {2, 400, 16},
                                       {3, 50, 8},   {3, 100, 8},  {3, 200, 8}}
               : std::vector<SlabSpec>{{2, 100, 16}, {2, 200, 16}};
  constexpr double kEta2 = 1.5, kEta3 = 1.8;
  std::vector<double> n2, e2, n3, e3;
  for (const SlabSpec& sp : specs) {
    const auto t0 = std::chrono::steady_clock::now();
    const double W = sp.rows * 0.5 / sp.n_left;
    SlabLevel L;
    if (sp.dim == 2) {
      auto gas = make_sod_slab(sp.n_left, sp.rows, kEta2);
      L = run_slab(*gas, rs, W, t0);
      n2.push_back(sp.n_left), e2.push_back(L.e.rho);
    } else {
      auto gas = make_sod_slab_3d(sp.n_left, sp.rows, kEta3);
      L = run_slab(*gas, rs, W * W, t0);
      n3.push_back(sp.n_left), e3.push_back(L.e.rho);
    }
    const double pp = L.plateau_p / rs.star().p;
    slab.rows.push_back({double(sp.dim), double(sp.n_left), double(sp.rows), double(L.n),
                         sp.dim == 2 ? kEta2 : kEta3, L.e.rho, L.e.v, L.e.p, L.e.u, pp, L.vperp,
                         L.e.overshoot_v, double(L.steps), L.secs});
    const std::string n =
        ", " + std::to_string(sp.dim) + "D slab, n_left = " + std::to_string(sp.n_left);
    res.figures.push_back(report("L1 error of rho" + n, L.e.rho));
    res.figures.push_back(report("L1 error of v" + n, L.e.v));
    res.figures.push_back(report("L1 error of p" + n, L.e.p));
    // The plateau is uniform in the exact solution; 2 % is twice the kernel-sampling bias of
    // the summation density on the stretched lattice (1.0 % for a 2.24 x 1 lattice, computed).
    res.figures.push_back(at_most("|plateau pressure / p* - 1|" + n, std::abs(pp - 1.0), 0.02));
    res.figures.push_back(at_most("RMS v_perp / v*" + n, L.vperp, 0.05));
    res.figures.push_back(report("largest post-shock overshoot of v / v*" + n, L.e.overshoot_v));
    res.figures.push_back(report("run time" + n, L.secs, "s"));
  }
  // The contact dominates the slabs' L1 error; smeared like sqrt(h) it converges at order
  // ~1/2 (the 1D tube, with equal masses, does better): judged at 0.3.
  res.figures.push_back(at_least("fitted L1 order of rho, 2D slab", fit_order(n2, e2), 0.3));
  if (n3.size() > 1)
    res.figures.push_back(at_least("fitted L1 order of rho, 3D slab", fit_order(n3, e3), 0.3));
  res.tables.push_back(errors);
  res.tables.push_back(profile);
  res.tables.push_back(slab);
  res.plots.push_back({"sod_density",
                       "Sod tube density at t = 0.2 (finest level)",
                       "sod_profile",
                       "x",
                       {"rho", "rho exact"},
                       false,
                       false,
                       "lines+points"});
  res.plots.push_back({"sod_velocity",
                       "Sod tube velocity at t = 0.2",
                       "sod_profile",
                       "x",
                       {"v", "v exact"},
                       false,
                       false,
                       "lines+points"});
  res.plots.push_back({"sod_pressure",
                       "Sod tube pressure at t = 0.2",
                       "sod_profile",
                       "x",
                       {"p", "p exact"},
                       false,
                       false,
                       "lines+points"});
  res.plots.push_back({"sod_errors",
                       "L1 errors against n_left",
                       "sod_errors",
                       "n_left",
                       {"L1 rho", "L1 v", "L1 p", "L1 u"},
                       true,
                       true,
                       "lines+points"});
  res.notes =
      "Sod shock tube (rho, p = 1, 1 | 0.125, 0.1, gamma 1.4) at t = 0.2 in 1D, equal-mass "
      "particles (spacing ratio 8), mirror walls at x = +-0.5, against the exact Riemann "
      "solution. L1 errors are volume-weighted (sum m/rho |q - q_exact|) over |x| < 0.4. "
      "Cubic spline, eta = 1.2, grad-h, Monaghan (1997) viscosity alpha = 1, beta = 2, "
      "kick-drift-kick leapfrog with the CFL step (0.3 h / v_sig). The 2D slab: the same "
      "tube on square lattices (spacing 0.5 / n_left left, twice that right, masses for the "
      "densities), 16 rows across y between mirror walls, cubic spline at eta = 1.5; the 3D "
      "slab: lattices of spacing d and 2d (equal masses), 8 x 8 rows across, Wendland C2 at "
      "eta = 1.8 (the --full form only). Why eta is raised in the slabs: a lattice crossing the "
      "fan is stretched along x only, and at eta = 1.2 the kernel no longer resolves the "
      "stretched direction (plateau pressure 8 % high in 2D, 29 % in 3D, at every resolution). "
      "Judged: the plateau pressure within 2 % of p*, the transverse velocity below 5 % of v*, "
      "the fitted L1 order of rho at least 0.3.";
  return res;
}

}  // namespace swell::verify
