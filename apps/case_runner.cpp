#include "apps/case_runner.hpp"

#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "bc/dbc.hpp"
#include "geometry/lattice_fill.hpp"
#include "io/vtk_writer.hpp"
#include "solver/diagnostics.hpp"

namespace swell {
namespace {

ViscosityModel viscosity_from(const std::string& s) {
  return s == "laminar" ? ViscosityModel::Laminar : ViscosityModel::Artificial;
}
DiffusionModel diffusion_from(const std::string& s) {
  if (s == "none") return DiffusionModel::None;
  if (s == "molteni") return DiffusionModel::MolteniColagrossi;
  return DiffusionModel::Fourtakas;
}

geometry::BodyGeometry to_geometry(const BodySpec& b) {
  geometry::BodyGeometry g;
  g.name = b.name;
  g.fluid = b.kind == BodySpec::Kind::Fluid;
  g.box = b.shape.box;
  g.walls_inside = b.walls == BodySpec::Walls::Inside;
  g.layers = b.layers;
  g.open = b.open;
  return g;
}

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  const long total = static_cast<long>(s + 0.5);
  std::ostringstream o;
  if (total >= 3600)
    o << total / 3600 << ":" << std::setw(2) << std::setfill('0') << (total / 60) % 60;
  else
    o << total / 60;
  o << ":" << std::setw(2) << std::setfill('0') << total % 60;
  return o.str();
}

}  // namespace

template <int D>
CaseSetup<D> setup_case(const CaseSpec& spec) {
  CaseSetup<D> s;
  geometry::FillOptions fo;
  fo.dim = D;
  fo.dp = spec.dp;
  std::vector<geometry::BodyGeometry> geo;
  for (const auto& b : spec.bodies) geo.push_back(to_geometry(b));
  const auto filled = geometry::fill_bodies(geo, fo);

  SolverParams& p = s.params;
  p.dp = spec.dp;
  p.h = spec.coefh * std::sqrt(static_cast<double>(D)) * spec.dp;
  p.kernel = kernel_from_name(spec.kernel);
  p.rho0 = spec.rho0;
  p.gravity = spec.gravity;
  if (D == 2) p.gravity.z() = 0.0;
  p.viscosity = viscosity_from(spec.viscosity_model);
  p.alpha = spec.alpha;
  p.nu = spec.nu;
  p.diffusion = diffusion_from(spec.diffusion_model);
  p.delta = spec.delta;
  p.integrator = spec.integrator == "verlet" ? IntegratorType::Verlet : IntegratorType::Symplectic;
  p.verlet_steps = spec.verlet_steps;
  p.cfl = spec.cfl;
  p.rho_min_factor = spec.rho_min_factor;
  p.rho_max_factor = spec.rho_max_factor;

  const double mass = spec.rho0 * std::pow(spec.dp, D);
  std::size_t total = 0;
  for (const auto& fb : filled) total += fb.points.size();
  s.particles.reserve(total);
  for (std::size_t b = 0; b < filled.size(); ++b) {
    const auto& fb = filled[b];
    s.bodies.push_back({fb.name, fb.fluid, fb.points.size()});
    for (const auto& x : fb.points)
      s.particles.add(x.template head<D>(), Vec<D>::Zero(), spec.rho0, mass,
                      fb.fluid ? Kind::Fluid : Kind::Boundary, static_cast<std::uint16_t>(b));
  }

  // Still-water height and c0 = coefsound sqrt(g H) (DualSPHysics' convention).
  const Vec<D> g = p.gravity.template head<D>();
  const double gnorm = g.norm();
  const Vec<D> up = gnorm > 0.0 ? Vec<D>(-g / gnorm) : Vec<D>::UnitY();
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    if (s.particles.kind[i] != Kind::Fluid) continue;
    const double z = s.particles.pos[i].dot(up);
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  if (!std::isfinite(zmin))
    throw std::invalid_argument(spec.file + ": the case holds no fluid particle");
  s.floor = zmin - 0.5 * spec.dp;
  s.hswl = spec.hswl ? *spec.hswl : (zmax - zmin + spec.dp);
  p.c0 = spec.coefsound * std::sqrt(std::max(gnorm, 1e-12) * s.hswl);

  // Domain: given, or the bounding box of all particles plus a margin (particles leaving it
  // are excluded). The margin leaves room for splashes above open tanks.
  Vec<D> lo = s.particles.pos[0], hi = s.particles.pos[0];
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    lo = lo.cwiseMin(s.particles.pos[i]);
    hi = hi.cwiseMax(s.particles.pos[i]);
  }
  const Vec<D> margin = (0.1 * (hi - lo)).array() + 2.0 * p.h;
  p.domain_min.setZero();
  p.domain_max.setZero();
  p.domain_min.template head<D>() =
      spec.domain_min ? Vec<D>(spec.domain_min->template head<D>()) : Vec<D>(lo - margin);
  p.domain_max.template head<D>() =
      spec.domain_max ? Vec<D>(spec.domain_max->template head<D>()) : Vec<D>(hi + margin);

  initialise_hydrostatic(s.particles, p);
  return s;
}

template CaseSetup<2> setup_case<2>(const CaseSpec&);
template CaseSetup<3> setup_case<3>(const CaseSpec&);

namespace {

template <int D>
RunSummary run_dim(const CaseSpec& spec, const RunOptions& opt) {
  std::ostream& log = opt.log ? *opt.log : std::cout;
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const std::string out_dir = opt.out_dir.empty() ? "out/" + spec.name : opt.out_dir;
  namespace fs = std::filesystem;
  fs::create_directories(fs::path(out_dir) / "vtk");

  const auto wall0 = std::chrono::steady_clock::now();
  CaseSetup<D> setup = setup_case<D>(spec);
  RunSummary sum;
  for (const auto& b : setup.bodies) (b.fluid ? sum.fluid : sum.boundary) += b.particles;

  log << "case " << spec.name << " (" << spec.file << "): " << D << "D, dp = " << spec.dp
      << " m, h = " << setup.params.h << " m, c0 = " << setup.params.c0 << " m/s, "
      << omp_get_max_threads() << " thread(s)\n";
  for (const auto& b : setup.bodies)
    log << "  body " << b.name << " (" << (b.fluid ? "fluid" : "boundary") << "): " << b.particles
        << " particles\n";
  log << "  total: " << sum.fluid + sum.boundary << " particles (" << sum.fluid << " fluid, "
      << sum.boundary << " boundary)\n";

  const Vec<D> g = setup.params.gravity.template head<D>();
  const Vec<D> up = g.norm() > 0.0 ? Vec<D>(-g / g.norm()) : Vec<D>::UnitY();
  const double floor = setup.floor, dp = spec.dp;
  const double band = 2.0 * setup.params.h;

  Simulation<D> sim(setup.params, std::move(setup.particles));
  const std::size_t n_total = sum.fluid + sum.boundary;

  PvdSeries pvd((fs::path(out_dir) / (spec.name + ".pvd")).string());
  std::ofstream diag(fs::path(out_dir) / "diagnostics.csv");
  if (!diag)
    throw std::runtime_error("cannot write " + (fs::path(out_dir) / "diagnostics.csv").string());
  diag << "# swell diagnostics for case " << spec.name << "; front = largest x of fluid within "
       << band << " m above the floor, plus dp/2\n";
  diag << "time [s],steps,dt [s],fluid particles,fluid mass [kg],kinetic energy [J],max speed "
          "[m/s],front x [m]\n";
  diag << std::setprecision(9);

  auto write_snapshot = [&]() {
    const double t0 = omp_get_wtime();
    if (spec.vtk) {
      char name[64];
      std::snprintf(name, sizeof(name), "%04d.vtp", sum.snapshots);
      const std::string rel = "vtk/" + spec.name + "_" + name;
      write_vtp<D>((fs::path(out_dir) / rel).string(), sim.particles(), sim.pressure());
      pvd.add(sim.time(), rel);
    }
    ++sum.snapshots;
    sum.output_seconds += omp_get_wtime() - t0;
  };
  auto write_diag = [&]() {
    const auto tot = fluid_totals(sim.particles());
    diag << sim.time() << ',' << sim.steps() << ',' << sim.dt() << ',' << tot.count << ','
         << tot.mass << ',' << tot.kinetic_energy << ',' << tot.max_speed << ','
         << surge_front(sim.particles(), up, floor, band, dp) << '\n';
  };

  const double t_end = spec.t_end;
  const double every = spec.output_every > 0.0 ? spec.output_every : t_end;
  const double diag_every = every / 10.0;
  double next_out = every, next_diag = diag_every;
  write_snapshot();
  write_diag();

  const bool tty = isatty(fileno(stderr));
  const auto loop0 = std::chrono::steady_clock::now();
  auto last_progress = loop0;
  long loop_steps = 0;
  while (sim.time() < t_end) {
    sim.step();
    ++loop_steps;
    if (sim.time() >= next_diag - 1e-12) {
      write_diag();
      while (next_diag <= sim.time() + 1e-12) next_diag += diag_every;
    }
    if (sim.time() >= next_out - 1e-12 || sim.time() >= t_end) {
      write_snapshot();
      while (next_out <= sim.time() + 1e-12) next_out += every;
    }
    const auto now = std::chrono::steady_clock::now();
    if (opt.progress && (now - last_progress > std::chrono::seconds(2) || sim.time() >= t_end)) {
      last_progress = now;
      const double el = std::chrono::duration<double>(now - loop0).count();
      const double rate = static_cast<double>(loop_steps) * n_total / std::max(el, 1e-9);
      const double eta = el / sim.time() * (t_end - sim.time());
      std::fprintf(
          stderr, "%st = %.4f / %.4f s | step %ld | dt %.3e s | %.2f M particle-steps/s | ETA %s%s",
          tty ? "\r" : "", sim.time(), t_end, sim.steps(), sim.dt(), rate / 1e6,
          format_duration(eta).c_str(), tty ? "   " : "\n");
      std::fflush(stderr);
    }
  }
  if (opt.progress && tty) std::fprintf(stderr, "\n");

  const auto wall1 = std::chrono::steady_clock::now();
  const double loop_s = std::chrono::duration<double>(wall1 - loop0).count();
  sum.wall_seconds = std::chrono::duration<double>(wall1 - wall0).count();
  sum.steps = sim.steps();
  sum.sim_time = sim.time();
  sum.particle_steps_per_second = static_cast<double>(n_total) * sum.steps / std::max(loop_s, 1e-9);
  sum.excluded = sim.excluded();
  sum.phases = sim.phase_times();

  std::ostringstream s;
  s << std::setprecision(4);
  s << "run summary: " << spec.name << "\n"
    << "  particles:      " << n_total << " (" << sum.fluid << " fluid, " << sum.boundary
    << " boundary)\n"
    << "  simulated time: " << sum.sim_time << " s in " << sum.steps << " steps\n"
    << "  wall time:      " << sum.wall_seconds << " s (time loop " << loop_s << " s, "
    << omp_get_max_threads() << " thread(s))\n"
    << "  speed:          " << sum.particle_steps_per_second / 1e6 << " M particle-steps/s, "
    << sum.steps / std::max(loop_s, 1e-9) << " steps/s\n"
    << "  phases:         neighbours " << sum.phases.neighbour << " s, interaction "
    << sum.phases.interaction << " s, integration " << sum.phases.integration << " s, output "
    << sum.output_seconds << " s\n"
    << "  excluded:       " << sum.excluded.total() << " (out of domain "
    << sum.excluded.out_of_domain << ", non-finite " << sum.excluded.non_finite
    << ", density out of range " << sum.excluded.density_out_of_range << ")\n"
    << "  output:         " << out_dir << " (" << sum.snapshots << " snapshots, " << pvd.path()
    << ")\n";
  log << s.str();
  std::ofstream(fs::path(out_dir) / "run_summary.txt") << s.str();
  return sum;
}

}  // namespace

RunSummary run_case(const CaseSpec& spec, const RunOptions& options) {
  if (spec.dim == 2) return run_dim<2>(spec, options);
  if (spec.dim == 3) return run_dim<3>(spec, options);
  throw std::invalid_argument(spec.file + ": dim must be 2 or 3");
}

}  // namespace swell
