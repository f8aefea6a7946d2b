// From a parsed case to particles, parameters and the simulation (io/case_setup.hpp).
#include "io/case_setup.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "bc/dbc.hpp"
#include "bc/mdbc.hpp"
#include "bc/moving_bodies.hpp"
#include "geometry/lattice_fill.hpp"
#include "geometry/wall_normals.hpp"
#include "io/case_file.hpp"
#include "io/case_geometry.hpp"

namespace swell {
template <int D>
CaseSetup<D> setup_case(const CaseSpec& spec) {
  CaseSetup<D> s;
  const auto fill0 = std::chrono::steady_clock::now();
  geometry::FillOptions fo;
  fo.dim = D;
  fo.dp = spec.dp;
  const std::vector<geometry::BodyGeometry> geo = case_geometry(spec, &s.meshes);
  std::vector<geometry::FilledBody> filled;
  try {
    filled = geometry::fill_bodies(geo, fo);
  } catch (const std::invalid_argument& e) {
    throw CaseError(spec.file, 0, e.what());
  }
  s.fill_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - fill0).count();

  SolverParams& p = s.params;
  p.dp = spec.dp;
  p.h = spec.coefh * std::sqrt(static_cast<double>(D)) * spec.dp;
  p.kernel = spec.kernel;
  p.rho0 = spec.rho0;
  p.gravity = spec.gravity;
  if (D == 2) p.gravity.z() = 0.0;
  p.viscosity = spec.viscosity_model;
  p.alpha = spec.alpha;
  p.nu = spec.nu;
  p.diffusion = spec.diffusion_model;
  p.delta = spec.delta;
  p.integrator = spec.integrator;
  p.verlet_steps = spec.verlet_steps;
  p.cfl = spec.cfl;
  p.rho_min_factor = spec.rho_min_factor;
  p.rho_max_factor = spec.rho_max_factor;
  p.boundary = spec.boundary;
  p.mdbc_slip = spec.mdbc_slip;
  p.mdbc_det_min = spec.mdbc_det_min;

  // Motion laws (checked here: a bad CSV series or spec is a case error at the body's line).
  s.motions.resize(spec.bodies.size());
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const BodySpec& body = spec.bodies[b];
    if (body.motion.type == MotionSpec::Type::None) continue;
    try {
      s.motions[b] = MotionLaw(body.motion);
    } catch (const std::invalid_argument& e) {
      throw CaseError(spec.file, body.line,
                      "bodies[" + std::to_string(b) + "].motion: " + std::string(e.what()));
    }
  }

  const double mass = spec.rho0 * std::pow(spec.dp, D);
  std::size_t total = 0;
  for (const auto& fb : filled) total += fb.points.size();
  s.particles.reserve(total);
  for (std::size_t b = 0; b < filled.size(); ++b) {
    const auto& fb = filled[b];
    const bool fluid = fb.report.fluid;
    s.bodies.push_back({fb.report.name, fluid, fb.points.size()});
    s.fill.push_back(fb.report);
    for (const auto& x : fb.points)
      s.particles.add(x.template head<D>(), Vec<D>::Zero(), spec.rho0, mass,
                      fluid ? Role::Fluid : Role::FixedWall, static_cast<std::uint16_t>(b));
  }

  // mDBC: each wall particle's vector to its wall surface, from its body's geometry.
  if (spec.boundary == BoundaryType::Mdbc) {
    std::vector<Vec<D>> normals;
    normals.reserve(total);
    for (std::size_t b = 0; b < filled.size(); ++b) {
      const auto& fb = filled[b];
      if (fb.report.fluid) {
        normals.resize(normals.size() + fb.points.size(), Vec<D>::Zero());
        continue;
      }
      std::vector<Eigen::Vector3d> n;
      try {
        n = geometry::wall_normals(geo[b], fb.points, fo);
      } catch (const std::invalid_argument& e) {
        throw CaseError(spec.file, spec.bodies[b].line, e.what());
      }
      for (const auto& v : n) normals.push_back(v.template head<D>());
    }
    s.particles.enable("normal", normals);
  }

  // Moving bodies' particles become moving walls, placed at their pose at t = 0.
  MovingBodies<D>::prepare(s.particles, s.motions);

  // Still-water height and c0 = coefsound sqrt(g H) (DualSPHysics' convention).
  const Vec<D> g = p.gravity.template head<D>();
  const double gnorm = g.norm();
  const Vec<D> up = gnorm > 0.0 ? Vec<D>(-g / gnorm) : Vec<D>::UnitY();
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    if (s.particles.role[i] != Role::Fluid) continue;
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
  // A moving body must never be excluded: the box holds its whole path up to time.end.
  for (std::size_t b = 0; b < s.motions.size(); ++b) {
    if (!s.motions[b].moves()) continue;
    Eigen::Vector3d blo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d bhi = -blo;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      if (s.particles.body[i] != b) continue;
      blo.template head<D>() = blo.template head<D>().cwiseMin(s.particles.pos_ref[i]);
      bhi.template head<D>() = bhi.template head<D>().cwiseMax(s.particles.pos_ref[i]);
    }
    if (D == 2) blo.z() = bhi.z() = 0.0;
    const auto corners = box_corners(blo, bhi);
    Eigen::Vector3d slo, shi;
    sweep_bounds(s.motions[b], spec.t_end, corners, slo, shi);
    lo = lo.cwiseMin(Vec<D>(slo.template head<D>()));
    hi = hi.cwiseMax(Vec<D>(shi.template head<D>()));
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

template <int D>
Simulation<D> make_simulation(const CaseSetup<D>& setup, ParticleSet<D> particles) {
  typename Simulation<D>::Hooks hooks;
  if (MovingBodies<D>::any_moves(setup.motions))
    hooks.push_back(std::make_unique<MovingBodies<D>>(setup.motions));
  std::unique_ptr<BoundaryModel<D>> wall =
      setup.params.boundary == BoundaryType::Mdbc
          ? make_mdbc<D>(setup.params.mdbc_slip, setup.params.mdbc_det_min)
          : make_dbc<D>();
  return Simulation<D>(setup.params, std::move(particles), std::move(wall), std::move(hooks));
}

template Simulation<2> make_simulation<2>(const CaseSetup<2>&, ParticleSet<2>);
template Simulation<3> make_simulation<3>(const CaseSetup<3>&, ParticleSet<3>);
template CaseSetup<2> setup_case<2>(const CaseSpec&);
template CaseSetup<3> setup_case<3>(const CaseSpec&);

}  // namespace swell
