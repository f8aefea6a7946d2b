#include "verify/flows.hpp"

#include <cmath>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bc/dbc.hpp"
#include "bc/mdbc.hpp"
#include "solver/time/shifting_hook.hpp"
#include "solver/time/simulation.hpp"
#include "verify/cloud.hpp"

namespace swell::verify {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// ---- Taylor-Green vortex ---------------------------------------------------------------------
// u = -U cos(kx) sin(ky), v = U sin(kx) cos(ky), p = -rho0 U^2 / 4 (cos 2kx + cos 2ky), k = 2 pi/L,
// in [0, L)^2 periodic on both axes; the velocity decays as exp(-2 nu k^2 t), the kinetic
// energy as exp(-16 pi^2 nu t / L^2) (Taylor & Green 1937).
struct Tgv {
  int n = 32;  // particles per side
  double L = 1.0, U = 1.0, nu = 0.01, c0 = 10.0, rho0 = 1000.0;
  IntegratorType integrator = IntegratorType::Symplectic;
  double fixed_dt = 0.0;
  bool shifting = false;  // Fickian particle shifting (solver/time/shifting_hook.hpp)
  double phase = 0.0;     // the vortex moved by (phase, phase) against the periodic faces
  double k() const { return 2.0 * kPi / L; }
  double energy_rate() const { return 16.0 * kPi * kPi * nu / (L * L); }
};

Simulation<2> make_tgv(const Tgv& c) {
  const double dp = c.L / c.n, k = c.k();
  SolverParams p;
  p.dp = dp;
  p.h = std::sqrt(2.0) * dp;  // coefh = 1
  p.gravity.setZero();
  p.c0 = c.c0;
  p.rho0 = c.rho0;
  p.viscosity = ViscosityModel::Laminar;
  p.nu = c.nu;
  p.integrator = c.integrator;
  p.fixed_dt = c.fixed_dt;
  p.domain_min = Eigen::Vector3d::Zero();
  p.domain_max = Eigen::Vector3d::Constant(c.L);
  p.periodic = {true, true, false};
  ParticleSet<2> ps;
  for (int j = 0; j < c.n; ++j)
    for (int i = 0; i < c.n; ++i) {
      const Vec<2> x((i + 0.5) * dp, (j + 0.5) * dp);
      const Vec<2> xs = x + Vec<2>::Constant(c.phase);
      const Vec<2> v(-c.U * std::cos(k * xs.x()) * std::sin(k * xs.y()),
                     c.U * std::sin(k * xs.x()) * std::cos(k * xs.y()));
      const double pr =
          -0.25 * c.rho0 * c.U * c.U * (std::cos(2.0 * k * xs.x()) + std::cos(2.0 * k * xs.y()));
      // Tait inverted: rho = rho0 (1 + P/B)^(1/gamma).
      const double rho = c.rho0 * std::pow(1.0 + pr / p.tait_b(), 1.0 / p.gamma);
      ps.add(x, v, rho, c.rho0 * dp * dp, Role::Fluid, 0);
    }
  Simulation<2>::Hooks hooks;
  if (c.shifting) hooks.push_back(std::make_unique<ShiftingHook<2>>(ShiftingParams{}));
  return Simulation<2>(p, std::move(ps), make_dbc<2>(), std::move(hooks));
}

double kinetic_energy(const ParticleSet<2>& ps) {
  double e = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) e += 0.5 * ps.mass[i] * ps.velocity(i).squaredNorm();
  return e;
}

struct TgvRun {
  double rate = 0.0;       // fitted decay rate of E over [t_fit0, t_end]
  double vel_error = 0.0;  // RMS |v - v_exact| / U at t_end
  long steps = 0;
  std::vector<double> t, e;  // E(t) / E(0) at every output
};

// Runs to t_end, fitting log E(t) by least squares over [0.1 t_end, t_end].
TgvRun run_tgv(const Tgv& c, double t_end) {
  Simulation<2> sim = make_tgv(c);
  TgvRun r;
  const double e0 = kinetic_energy(sim.particles());
  const double every = t_end / 50.0;
  double next = 0.0;
  double st = 0, se = 0, stt = 0, ste = 0;
  int m = 0;
  auto sample = [&] {
    const double t = sim.time(), e = kinetic_energy(sim.particles()) / e0;
    r.t.push_back(t);
    r.e.push_back(e);
    if (t >= 0.1 * t_end) {
      const double y = std::log(e);
      st += t, se += y, stt += t * t, ste += t * y, ++m;
    }
  };
  while (sim.time() < t_end) {
    if (sim.time() >= next) {
      sample();
      next += every;
    }
    sim.step();
  }
  sample();
  r.rate = -(m * ste - st * se) / (m * stt - st * st);
  r.steps = sim.steps();
  const double k = c.k(), decay = std::exp(-2.0 * c.nu * k * k * sim.time());
  double err2 = 0.0;
  const auto& ps = sim.particles();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Vec<2> x = ps.pos[i] + Vec<2>::Constant(c.phase);
    const Vec<2> ve(-c.U * decay * std::cos(k * x.x()) * std::sin(k * x.y()),
                    c.U * decay * std::sin(k * x.x()) * std::cos(k * x.y()));
    err2 += (ps.velocity(i) - ve).squaredNorm();
  }
  r.vel_error = std::sqrt(err2 / ps.size()) / (c.U * decay);
  return r;
}

// ---- Poiseuille flow -------------------------------------------------------------------------
// Fluid between plates at y = 0 and y = H, driven from rest by a body force F along x:
// u(y, t) = F/(2 nu) y (H - y) - sum_n 4 F H^2 / (nu pi^3 (2n+1)^3) sin((2n+1) pi y / H)
//           exp(-(2n+1)^2 pi^2 nu t / H^2)   (Morris, Fox & Zhu 1997, eq. 21).
double poiseuille_u(double y, double t, double F, double nu, double H) {
  double u = F / (2.0 * nu) * y * (H - y);
  for (int n = 0; n < 200; ++n) {
    const double m = 2.0 * n + 1.0;
    u -= 4.0 * F * H * H / (nu * kPi * kPi * kPi * m * m * m) * std::sin(m * kPi * y / H) *
         std::exp(-m * m * kPi * kPi * nu * t / (H * H));
  }
  return u;
}

}  // namespace

Result run_taylor_green(const Options& opt) {
  Result r;
  const double t_end = 0.5;
  // Re = U L / nu = 1 (U = 0.01 m/s): viscous decay of a nearly undeformed lattice, the check of
  // the periodic images and the Morris viscous term; Re = 100 (U = 1 m/s): the classic case,
  // where particles stretched at the stagnation points disorder the set.
  const std::vector<int> sides =
      opt.full ? std::vector<int>{32, 64, 128} : std::vector<int>{32, 64};
  struct Variant {
    std::string label;
    double U;
    bool shifting;
    std::vector<int> sides;
  };
  const std::vector<Variant> variants = {
      {"Re 1", 0.01, false, sides},
      {"Re 100", 1.0, false, opt.full ? sides : std::vector<int>{32}},
      {"Re 100 shifting", 1.0, true, opt.full ? sides : std::vector<int>{32}},
  };
  Table decay{"taylor_green_energy", {"t [s]"}, {}};
  Table conv{"taylor_green_convergence",
             {"Re", "shifting", "particles per side", "dp [m]", "decay rate", "exact rate",
              "decay rate error"},
             {}};
  std::vector<TgvRun> runs;
  std::vector<double> rate_exact;
  double stokes_coarse = NAN, stokes_fine = NAN;
  for (const Variant& v : variants) {
    for (int n : v.sides) {
      Tgv c;
      c.U = v.U;
      c.shifting = v.shifting;
      c.n = n;
      runs.push_back(run_tgv(c, t_end));
      rate_exact.push_back(c.energy_rate());
      const TgvRun& t = runs.back();
      const double rel = std::abs(t.rate - c.energy_rate()) / c.energy_rate();
      const double re = c.U * c.L / c.nu;
      conv.rows.push_back(
          {re, v.shifting ? 1.0 : 0.0, double(n), c.L / n, t.rate, c.energy_rate(), rel});
      decay.columns.push_back("E/E0 " + v.label + " " + std::to_string(n) + "^2");
      const std::string what = v.label + ", " + std::to_string(n) + "^2";
      if (v.U < 0.1) {
        r.figures.push_back(at_most("decay rate relative error, " + what, rel, 0.05));
        if (n == v.sides.front()) stokes_coarse = rel;
        if (n == v.sides.back()) stokes_fine = rel;
      } else {
        r.figures.push_back(report("decay rate relative error, " + what, rel));
      }
    }
  }
  r.figures.push_back(at_most("Re 1: error at the finest resolution / error at 32^2",
                              stokes_fine / stokes_coarse, 1.0));
  decay.columns.push_back("E/E0 exact");
  for (std::size_t k = 0; k < runs[0].t.size(); ++k) {
    std::vector<double> row{runs[0].t[k]};
    for (std::size_t j = 0; j < runs.size(); ++j) {
      // E/E0 divided by the exact decay of its own case, so both Re share one axis.
      const double scale =
          std::exp(-rate_exact[j] * runs[0].t[k]) / std::exp(-rate_exact[0] * runs[0].t[k]);
      row.push_back(k < runs[j].e.size() ? runs[j].e[k] / scale : NAN);
    }
    row.push_back(std::exp(-rate_exact[0] * runs[0].t[k]));
    decay.rows.push_back(row);
  }
  r.tables.push_back(decay);
  r.tables.push_back(conv);
  Plot pe{"taylor_green_energy",
          "Taylor-Green vortex: E/E0, scaled to the Re = 1 decay (exact: one line)",
          "taylor_green_energy",
          "t [s]",
          {},
          false,
          true,
          "lines"};
  for (std::size_t k = 1; k < decay.columns.size(); ++k) pe.y.push_back(decay.columns[k]);
  r.plots.push_back(pe);
  r.notes =
      "The 2D Taylor-Green vortex in the doubly periodic unit box (periodic images, "
      "solver/neighbours/cell_grid.hpp), nu = 0.01 m^2/s, c0 = 10 m/s, laminar (Lo & Shao / "
      "Morris) viscosity, Fourtakas density diffusion (delta = 0.1), Wendland kernel with "
      "h = sqrt(2) dp, symplectic integrator, CFL 0.2; initial density from the exact pressure "
      "-rho0 U^2/4 (cos 2kx + cos 2ky) through the Tait equation. The kinetic energy must decay "
      "as exp(-16 pi^2 nu t / L^2); the rate is fitted to log E over t = 0.05-0.5 s. At Re = 1 "
      "(U = 0.01 m/s) the particles hardly move and the decay checks the viscous term across "
      "the periodic faces (bound 5 %). At Re = 100 (U = 1 m/s) the standard weakly compressible "
      "scheme breaks down: the kinetic energy follows the exact decay to t ~ 0.1 s and then "
      "collapses, at the same time at every resolution and with the vortex's phase moved "
      "against the periodic faces (measured: the same rate to 10 digits), i.e. the particle "
      "disorder at the stagnation points, not the faces; Fickian shifting delays it. These "
      "figures are reported, not judged: a transport-velocity or delta+-SPH formulation is "
      "what the literature uses for this case.";
  return r;
}

namespace {

// Plane Poiseuille flow in a channel periodic along x between wall-particle plates.
struct PoiseuilleRun {
  std::vector<double> y, u_sph, u_exact;  // per particle row, at each sample time
  std::vector<double> t, max_err, rms_err;
  double offset = 0.0;     // fitted no-slip offset delta (the walls act at -delta, H + delta)
  double shape_rms = 0.0;  // RMS of u - F/(2 nu)(y + delta)(H + delta - y), / u_max
};

PoiseuilleRun run_channel(int ny, BoundaryType boundary, const std::vector<double>& times, double H,
                          double nu, double F) {
  const double c0 = 2.0, rho0 = 1000.0, u_max = F * H * H / (8.0 * nu);
  const int nx = 8, layers = 3;
  const double dp = H / ny;
  SolverParams p;
  p.dp = dp;
  p.h = std::sqrt(2.0) * dp;
  p.gravity = Eigen::Vector3d(F, 0.0, 0.0);
  p.c0 = c0;
  p.rho0 = rho0;
  p.viscosity = ViscosityModel::Laminar;
  p.nu = nu;
  p.boundary = boundary;
  p.domain_min = Eigen::Vector3d(0.0, -(layers + 1) * dp, 0.0);
  p.domain_max = Eigen::Vector3d(nx * dp, H + (layers + 1) * dp, 1.0);
  p.periodic = {true, false, false};
  ParticleSet<2> ps;
  std::vector<Vec<2>> normals;
  for (int i = 0; i < nx; ++i) {
    const double x = (i + 0.5) * dp;
    for (int j = 0; j < ny; ++j) {
      ps.add(Vec<2>(x, (j + 0.5) * dp), Vec<2>::Zero(), rho0, rho0 * dp * dp, Role::Fluid, 0);
      normals.push_back(Vec<2>::Zero());
    }
    for (int k = 0; k < layers; ++k) {
      // mDBC: the vector from a wall particle to the wall surface (y = 0 or y = H).
      ps.add(Vec<2>(x, -(k + 0.5) * dp), Vec<2>::Zero(), rho0, rho0 * dp * dp, Role::FixedWall, 1);
      normals.push_back(Vec<2>(0.0, (k + 0.5) * dp));
      ps.add(Vec<2>(x, H + (k + 0.5) * dp), Vec<2>::Zero(), rho0, rho0 * dp * dp, Role::FixedWall,
             1);
      normals.push_back(Vec<2>(0.0, -(k + 0.5) * dp));
    }
  }
  std::unique_ptr<BoundaryModel<2>> bm;
  if (boundary == BoundaryType::Mdbc) {
    ps.enable("normal", normals);
    bm = make_mdbc<2>(MdbcSlip::NoSlip, p.mdbc_det_min);
  } else {
    bm = make_dbc<2>();
  }
  Simulation<2> sim(p, std::move(ps), std::move(bm));
  PoiseuilleRun out;
  std::vector<double> sum(ny), ysum(ny);
  std::vector<int> cnt(ny);
  for (double ts : times) {
    while (sim.time() < ts) sim.step();
    const auto& q = sim.particles();
    std::fill(sum.begin(), sum.end(), 0.0);
    std::fill(ysum.begin(), ysum.end(), 0.0);
    std::fill(cnt.begin(), cnt.end(), 0);
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (!is_fluid(q.role[i])) continue;
      const int j = static_cast<int>(std::floor(q.pos[i].y() / dp));
      if (j < 0 || j >= ny) continue;
      sum[j] += q.velocity(i).x();
      ysum[j] += q.pos[i].y();
      ++cnt[j];
    }
    double emax = 0.0, e2 = 0.0;
    int nb = 0;
    for (int j = 0; j < ny; ++j) {
      const double y = cnt[j] ? ysum[j] / cnt[j] : (j + 0.5) * dp;
      const double u = cnt[j] ? sum[j] / cnt[j] : NAN;
      const double ue = poiseuille_u(y, sim.time(), F, nu, H);
      out.y.push_back(y);
      out.u_sph.push_back(u / u_max);
      out.u_exact.push_back(ue / u_max);
      if (!cnt[j]) continue;
      emax = std::max(emax, std::abs(u - ue) / u_max);
      e2 += (u - ue) * (u - ue);
      ++nb;
    }
    out.t.push_back(sim.time());
    out.max_err.push_back(emax);
    out.rms_err.push_back(nb ? std::sqrt(e2 / nb) / u_max : NAN);
  }
  // The steady profile with the no-slip planes moved out by delta: u = F/(2 nu)(y + d)(H + d - y);
  // delta by least squares (one unknown, scanned then refined), on the last sample.
  const std::size_t base = out.y.size() - static_cast<std::size_t>(ny);
  auto residual = [&](double d) {
    double e2 = 0.0;
    for (int j = 0; j < ny; ++j) {
      const double y = out.y[base + j];
      const double uf = F / (2.0 * nu) * (y + d) * (H + d - y) / u_max;
      e2 += std::pow(out.u_sph[base + j] - uf, 2);
    }
    return std::sqrt(e2 / ny);
  };
  double lo = -dp, hi = 3.0 * dp;
  for (int it = 0; it < 100; ++it) {  // golden-section search: the residual is convex in d
    const double m1 = lo + 0.382 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
    if (residual(m1) < residual(m2))
      hi = m2;
    else
      lo = m1;
  }
  out.offset = 0.5 * (lo + hi);
  out.shape_rms = residual(out.offset);
  return out;
}

}  // namespace

Result run_poiseuille(const Options& opt) {
  Result r;
  const double H = 0.1, nu = 0.01, F = 0.8;
  const double u_max = F * H * H / (8.0 * nu);
  const std::vector<double> times = {0.05, 0.1, 0.2, 0.5, 1.0};
  const std::vector<int> resolutions =
      opt.full ? std::vector<int>{20, 40, 80} : std::vector<int>{20};
  Table prof{"poiseuille_profile", {"y/H"}, {}};
  Table err{"poiseuille_error",
            {"boundary (0 DBC; 1 mDBC)", "H/dp", "t [s]", "max error / u_max", "RMS error / u_max"},
            {}};
  Table off{"poiseuille_offset",
            {"boundary (0 DBC; 1 mDBC)", "H/dp", "no-slip offset / dp", "shape RMS / u_max"},
            {}};
  const int ny_profile = resolutions.front();
  for (BoundaryType bt : {BoundaryType::Dbc, BoundaryType::Mdbc}) {
    const std::string bname = bt == BoundaryType::Dbc ? "DBC" : "mDBC no-slip";
    for (int ny : resolutions) {
      const PoiseuilleRun run = run_channel(ny, bt, times, H, nu, F);
      const double dp = H / ny;
      for (std::size_t s = 0; s < run.t.size(); ++s)
        err.rows.push_back({bt == BoundaryType::Dbc ? 0.0 : 1.0, double(ny), run.t[s],
                            run.max_err[s], run.rms_err[s]});
      off.rows.push_back(
          {bt == BoundaryType::Dbc ? 0.0 : 1.0, double(ny), run.offset / dp, run.shape_rms});
      const std::string what = bname + ", H/dp = " + std::to_string(ny);
      r.figures.push_back(report("steady max |u - u_exact| / u_max, " + what, run.max_err.back()));
      // The no-slip plane lies within one dp of the wall surface (DBC: the wall particles' first
      // row is dp/2 inside the wall); the profile, moved by that offset, is the parabola to 2 %
      // (the viscous term itself: `laplacian` is within ~2 % on a lattice).
      r.figures.push_back(at_most("no-slip offset / dp, " + what, std::abs(run.offset) / dp, 1.0));
      r.figures.push_back(
          at_most("shape RMS / u_max after the offset, " + what, run.shape_rms, 0.02));
      if (ny != ny_profile) continue;
      const std::size_t nt = run.t.size();
      if (prof.rows.empty())
        for (int j = 0; j < ny; ++j) prof.rows.push_back({run.y[j] / H});
      for (std::size_t s = 0; s < nt; ++s) {
        prof.columns.push_back(bname + " t = " + num(times[s]) + " s");
        for (int j = 0; j < ny; ++j) prof.rows[j].push_back(run.u_sph[s * ny + j]);
      }
      if (bt == BoundaryType::Dbc)
        for (std::size_t s = 0; s < nt; ++s) {
          prof.columns.push_back("exact t = " + num(times[s]) + " s");
          for (int j = 0; j < ny; ++j) prof.rows[j].push_back(run.u_exact[s * ny + j]);
        }
    }
  }
  r.tables.push_back(prof);
  r.tables.push_back(err);
  r.tables.push_back(off);
  Plot pp{"poiseuille_profile",
          "Poiseuille flow from rest, H/dp = " + std::to_string(ny_profile) +
              ": u/u_max at t = 0.1 and 1 s",
          "poiseuille_profile",
          "y/H",
          {},
          false,
          false,
          "lines+points"};
  // Two of the times in the plot (all in the table): the developing and the steady profile.
  for (const char* t : {"0.1", "1"})
    for (const char* b : {"exact", "DBC", "mDBC no-slip"})
      pp.y.push_back(std::string(b) + " t = " + t + " s");
  r.plots.push_back(pp);
  r.notes =
      "Plane Poiseuille flow started from rest: plates at y = 0 and H = 0.1 m (three "
      "layers of wall particles each, DBC or mDBC with the no-slip velocity), periodic "
      "along x (8 particles), body force F = 0.8 m/s^2 along x, nu = 0.01 m^2/s (u_max = " +
      num(u_max) +
      " m/s, Re = 1), c0 = 2 m/s, laminar viscosity, symplectic. The mean u of each "
      "particle row is compared with the series solution (Morris et al. 1997, eq. 21) at "
      "the row's mean y at t = 0.05-1 s (t = 1 s is steady to 5e-5). The steady profile "
      "is then fitted with the no-slip planes moved out by an offset delta: DBC's "
      "effective wall lies beyond the wall surface, so its velocities are too high by "
      "about 4 delta / H at mid-channel.";
  return r;
}

Result run_time_order(const Options& opt) {
  Result r;
  const double t_end = 0.1, dt0 = 1e-3;
  const int levels = opt.full ? 5 : 4, ref_div = 64;
  Tgv c;
  c.n = opt.full ? 32 : 24;
  // The final positions and velocities by particle id.
  auto final_state = [&](IntegratorType integ, double dt, std::vector<Vec<2>>& x,
                         std::vector<Vec<2>>& v) {
    Tgv cc = c;
    cc.integrator = integ;
    cc.fixed_dt = dt;
    Simulation<2> sim = make_tgv(cc);
    const long steps = std::lround(t_end / dt);
    for (long s = 0; s < steps; ++s) sim.step();
    const auto& ps = sim.particles();
    x.assign(ps.total(), Vec<2>::Zero());
    v.assign(ps.total(), Vec<2>::Zero());
    for (std::size_t i = 0; i < ps.size(); ++i)
      x[ps.id[i]] = ps.pos[i], v[ps.id[i]] = ps.velocity(i);
  };
  Table t{"time_order",
          {"dt [s]", "symplectic position error [m]", "symplectic velocity error [m/s]",
           "Verlet position error [m]", "Verlet velocity error [m/s]"},
          {}};
  std::vector<std::vector<double>> cols(4);
  std::vector<double> dts;
  const IntegratorType kinds[2] = {IntegratorType::Symplectic, IntegratorType::Verlet};
  std::vector<Vec<2>> xr[2], vr[2];
  for (int k = 0; k < 2; ++k) final_state(kinds[k], dt0 / ref_div, xr[k], vr[k]);
  for (int l = 0; l < levels; ++l) {
    const double dt = dt0 / std::pow(2.0, l);
    dts.push_back(dt);
    std::vector<double> row{dt};
    for (int k = 0; k < 2; ++k) {
      std::vector<Vec<2>> x, v;
      final_state(kinds[k], dt, x, v);
      double ex = 0.0, ev = 0.0;
      for (std::size_t i = 0; i < x.size(); ++i) {
        // Positions compared modulo the period (a particle may sit across a face in one run).
        Vec<2> d = x[i] - xr[k][i];
        for (int a = 0; a < 2; ++a) d[a] -= c.L * std::round(d[a] / c.L);
        ex += d.squaredNorm();
        ev += (v[i] - vr[k][i]).squaredNorm();
      }
      ex = std::sqrt(ex / x.size());
      ev = std::sqrt(ev / x.size());
      cols[2 * k].push_back(ex);
      cols[2 * k + 1].push_back(ev);
      row.push_back(ex);
      row.push_back(ev);
    }
    t.rows.push_back(row);
  }
  const double sx = fitted_order(dts, cols[0]), sv = fitted_order(dts, cols[1]);
  const double vx = fitted_order(dts, cols[2]), vv = fitted_order(dts, cols[3]);
  // With velocities stored in float (types.hpp) the runs differ by their rounding, ~1e-5 of the
  // velocity after the reference's 6,400 steps (measured: the errors stop falling at ~5e-7 m
  // and ~1e-5 m/s from dt = 5e-4 s), which hides the truncation error: the order is checked in
  // a build with -DSWELL_DOUBLE_STATE=ON (.ci/run builds one) and only reported in the other.
  if (kStateEps < 1e-10) {
    r.figures.push_back(at_least("symplectic: order of the position error", sx, 1.8));
    r.figures.push_back(at_least("symplectic: order of the velocity error", sv, 1.8));
  } else {
    r.figures.push_back(report("symplectic: order of the position error (float state)", sx));
    r.figures.push_back(report("symplectic: order of the velocity error (float state)", sv));
  }
  r.figures.push_back(report("Verlet (Euler step every 40): order of the position error", vx));
  r.figures.push_back(report("Verlet (Euler step every 40): order of the velocity error", vv));
  r.tables.push_back(t);
  r.plots.push_back({"time_order",
                     "Temporal convergence at fixed dt (Taylor-Green, t = 0.1 s)",
                     "time_order",
                     "dt [s]",
                     {"symplectic position error [m]", "symplectic velocity error [m/s]",
                      "Verlet position error [m]", "Verlet velocity error [m/s]"},
                     true,
                     true,
                     "lines+points"});
  r.notes = "The Taylor-Green vortex of `taylor_green` (" + std::to_string(c.n) +
            "^2 particles) "
            "run to t = 0.1 s at fixed dt = 1e-3 s / 2^k (SolverParams::fixed_dt; the CFL step "
            "here is ~1.2e-3 s), each against the same integrator at dt / " +
            std::to_string(ref_div) +
            ": RMS over the particles (matched by id) of the position and velocity differences; "
            "orders fitted by least squares in log-log. The symplectic scheme is second order. "
            "Verlet's Euler step every 40 steps (as DualSPHysics) is a first-order step whose "
            "count grows as dt falls, so its order lies between one and two. The symplectic "
            "order is checked (>= 1.8) only where velocity and density are stored in double "
            "(-DSWELL_DOUBLE_STATE=ON): with the default float storage the rounding of the "
            "stored velocities (~1e-5 of them after the reference's 6,400 steps) is larger than "
            "the truncation error below dt = 1e-3 s, and the figures are reported only.";
  return r;
}

}  // namespace swell::verify
