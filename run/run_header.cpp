#include "run/run_header.hpp"

#include <omp.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "bc/absorption.hpp"
#include "case/model_names.hpp"
#include "solver/physics/shifting.hpp"

namespace swell {
namespace {

// The damping zones for the run header, one clause each.
std::string damping_text(const std::vector<DampingZone>& zones, int dim) {
  if (zones.empty()) return "none";
  auto point = [dim](const Eigen::Vector3d& x) {
    std::ostringstream o;
    o << "(";
    for (int d = 0; d < dim; ++d) o << (d ? ", " : "") << x[d];
    return o.str() + ")";
  };
  std::ostringstream o;
  o << zones.size() << (zones.size() == 1 ? " zone" : " zones") << ", v *= exp(-sigma dt): ";
  for (std::size_t k = 0; k < zones.size(); ++k) {
    const DampingZone& z = zones[k];
    const DampingGeometry g = damping_geometry(z, dim);
    o << (k ? "; " : "") << z.name << " (";
    if (z.shape == DampingZone::Shape::Plane)
      o << "plane from " << point(z.at) << " along " << point(g.n) << ", L = " << g.length << " m";
    else
      o << "box " << point(z.box_min) << " - " << point(z.box_max) << " along " << point(g.n)
        << ", L = " << g.length << " m";
    o << ", sigma = " << z.rate
      << (z.ramp == DampingRamp::Quadratic ? " s^2" : " (1 - cos(pi s)) / 2") << " 1/s";
    bool all = true;
    for (int d = 0; d < dim; ++d) all = all && z.components[static_cast<std::size_t>(d)];
    if (!all) {
      o << ", components";
      for (int d = 0; d < dim; ++d)
        if (z.components[static_cast<std::size_t>(d)])
          o << " "
            << "xyz"[d];
    }
    if (z.start > 0.0 || std::isfinite(z.stop))
      o << ", t in [" << z.start << ", " << z.stop << ") s";
    o << ")";
  }
  return o.str();
}

// The derived quantities of the run header: each with the formula the set-up and the solver use,
// its inputs and its value (docs/case_reference.md, "Derived quantities"; checked by
// tests/test_case_reference.cpp).
template <int D>
std::string derived_quantities_text(const CaseSpec& spec, const CaseSetup<D>& setup) {
  const SolverParams& p = setup.params;
  const double g = p.gravity.template head<D>().norm();
  const double support = kernel_support_factor(p.kernel);
  const double mass = setup.particles.size() > 0 ? setup.particles.mass[0] : 0.0;
  const bool laminar = p.viscosity == ViscosityModel::Laminar && p.nu > 0.0;
  const int layers = static_cast<int>(std::ceil(support * p.h / p.dp - 0.5));
  std::ostringstream o;
  o << std::setprecision(10);
  o << "  derived quantities (formula = inputs = value):\n";
  o << "    h = coefh * sqrt(dim) * dp = " << spec.coefh << " * sqrt(" << D << ") * " << p.dp
    << " = " << p.h << " m\n";
  o << "    support = " << support << " h = " << support * p.h << " m (kernel "
    << kernel_name(p.kernel) << ")\n";
  o << "    hswl = " << (spec.hswl ? "physics.hswl" : "top - bottom fluid particle + dp") << " = "
    << setup.hswl << " m\n";
  o << "    c0 = coefsound * sqrt(|g| * hswl) = " << spec.coefsound << " * sqrt(" << g << " * "
    << setup.hswl << ") = " << p.c0 << " m/s\n";
  o << "    B = c0^2 * rho0 / gamma = " << p.c0 << "^2 * " << p.rho0 << " / " << p.gamma << " = "
    << p.tait_b() << " Pa\n";
  o << "    mass = rho0 * dp^dim = " << p.rho0 << " * " << p.dp << "^" << D << " = " << mass
    << (D == 2 ? " kg/m (per metre of depth)\n" : " kg\n");
  o << "    dt = cfl * min(dt_f, dt_cv" << (laminar ? ", dt_nu" : "") << "), cfl = " << p.cfl
    << ": dt_f = sqrt(h / max|a|), dt_cv = h / (max c + max_ab h |v_ab.r_ab| / (r_ab^2 + "
       "eta^2)), eta^2 = 0.01 h^2 = "
    << p.eta2() << " m^2";
  if (laminar) o << ", dt_nu = 0.125 h^2 / nu = " << 0.125 * p.h * p.h / p.nu << " s";
  o << "\n";
  o << "    dt at rest: cfl * h / c0 = " << p.cfl * p.h / p.c0
    << " s, cfl * sqrt(h / |g|) = " << p.cfl * std::sqrt(p.h / g) << " s\n";
  o << "    wall layers for the full support: ceil(support / dp - 1/2) = " << layers;
  std::string thin;
  for (const BodySpec& b : spec.bodies)
    if (b.kind == BodySpec::Kind::Boundary && b.layers < layers)
      thin += (thin.empty() ? "" : ", ") + b.name + " " + std::to_string(b.layers);
  if (!thin.empty()) o << " (fewer: " << thin << ")";
  o << "\n";
  return o.str();
}

}  // namespace

template <int D>
std::string run_header(const CaseSpec& spec, const CaseSetup<D>& setup, int ranks) {
  std::size_t fluid = 0, boundary = 0;
  for (const auto& b : setup.bodies) (b.fluid ? fluid : boundary) += b.particles;
  const std::size_t n_total = fluid + boundary;
  std::ostringstream o;
  o << "case " << spec.name << " (" << spec.file << "): " << D << "D, dp = " << spec.dp
    << " m, h = " << setup.params.h << " m, c0 = " << setup.params.c0 << " m/s, "
    << omp_get_max_threads() << " thread(s)"
    << (ranks > 1 ? " on each of " + std::to_string(ranks) + " MPI ranks" : "") << "\n";
  for (const auto& b : setup.bodies)
    o << "  body " << b.name << " (" << (b.fluid ? "fluid" : "boundary") << "): " << b.particles
      << " particles\n";
  o << "  total: " << n_total << " particles (" << fluid << " fluid, " << boundary
    << " boundary)\n";
  {
    const auto& pr = setup.params;
    std::ostringstream d;
    for (int k = 0; k < D; ++k)
      d << (k ? " x " : "") << "[" << pr.domain_min[k] << ", " << pr.domain_max[k] << "]";
    o << "  domain: " << d.str() << " m"
      << (setup.default_domain ? " (default: the particles' box + 10 % + 2h, +50 % of its "
                                 "height above; set domain: to change)"
                               : " (from the case file)")
      << "\n";
  }
  o << derived_quantities_text(spec, setup);
  {
    const auto& pr = setup.params;
    o << "  walls: " << boundary_name(pr.boundary);
    if (pr.boundary == BoundaryType::Mdbc) {
      o << " (slip " << mdbc_slip_name(pr.mdbc_slip) << ", pressure "
        << mdbc_pressure_name(pr.mdbc_pressure) << ", det_min " << pr.mdbc_det_min << ")";
      std::string dbc;  // bodies[].boundary: dbc inside an mDBC run
      for (std::size_t b = 0; b < setup.dbc_bodies.size(); ++b)
        if (setup.dbc_bodies[b]) dbc += (dbc.empty() ? "" : ", ") + setup.bodies[b].name;
      if (!dbc.empty()) o << ", DBC walls on " << dbc;
    }
    o << "; shifting: " << shifting_name(pr.shifting);
    if (pr.shifting == ShiftingModel::Fickian) {
      ShiftingParams sp;
      sp.surface_threshold = pr.shift_surface_threshold;
      o << " (dr = -A h |v| dt grad C, A = " << pr.shift_coefficient
        << ", free surface where div r < " << sp.threshold(D)
        << ", near walls: " << shift_mode_name(pr.shift_mode)
        << (pr.shift_correct_density ? ", density moved with the shift" : "") << ")";
    }
    o << "\n";
  }
  bool short_h_noted = false, artificial_noted = false;
  for (const auto& b : spec.bodies) {
    if (b.motion.type != MotionSpec::Type::Wave) continue;
    o << "  wavemaker " << b.name << ": " << b.motion.wave_label << "\n";
    // Measured on cases/wave_decay2d.yaml at H/dp 5 (docs/validation/wave_decay.md): 44 % of the
    // height lost over three wavelengths at coefh 1, 12-15 % at coefh 1.2, 1.5 and 2.
    if (spec.coefh < 1.2 && !short_h_noted) {
      o << "  warning: wavemaker " << b.name << ": coefh " << spec.coefh
        << " < 1.2: a wave loses much of its height over a few wavelengths with this short "
           "smoothing length (measured: 44 % over three wavelengths at coefh 1 against 12 % "
           "at 1.5, H/dp 5); consider physics.coefh: 1.5\n";
      short_h_noted = true;
    }
    // The same case at coefh 1.5, H/dp 5: 11.9 % lost over three wavelengths with artificial
    // viscosity alpha 0.01 (nu = alpha h c0 / 2 (D + 2), Monaghan 1992), 4.2 % with alpha
    // 0.001, 3.5 % with water's laminar viscosity (docs/validation/wave_decay.md).
    if (spec.viscosity_model == ViscosityModel::Artificial && spec.alpha > 0.001 &&
        !artificial_noted) {
      o << "  warning: wavemaker " << b.name << ": artificial viscosity alpha " << spec.alpha
        << " damps the wave like a viscosity alpha h c0 / " << 2 * (D + 2) << " = "
        << spec.alpha * setup.params.h * setup.params.c0 / (2 * (D + 2))
        << " m^2/s (measured at coefh 1.5, H/dp 5: 11.9 % of the height lost over three "
           "wavelengths with alpha 0.01 against 3.5 % with water's viscosity); consider "
           "physics.viscosity: {model: laminar, nu: 1.0e-6}\n";
      artificial_noted = true;
    }
    for (const auto& w : b.motion.wave_notes)
      o << "  warning: wavemaker " << b.name << ": " << w << "\n";
    if (b.motion.absorption) {
      const PaddleAbsorber a(b.motion);
      const auto& ab = *b.motion.absorption;
      o << "  absorption " << b.name << ": U_c = G (eta_T - eta_M), G = "
        << (ab.gain == MotionSpec::Absorption::Gain::Tuned ? "w_p / F(k_p d)" : "sqrt(g / d)")
        << " = " << a.gain() << " 1/s; eta_M on the line "
        << (ab.distance ? std::to_string(*ab.distance) + " m" : std::string("one support"))
        << " in front of the face, low-pass " << a.filter_time() << " s, drift " << a.drift_time()
        << " s\n";
    }
  }
  o << "  damping: " << damping_text(setup.damping, D) << "; settling: ";
  if (setup.settling)
    o << "t < " << setup.settling->duration
      << " s, v *= exp(-sigma dt), sigma = " << setup.settling->rate << " (1 + cos(pi t / "
      << setup.settling->duration << " s)) / 2 1/s";
  else
    o << "none";
  o << "\n";
  for (const auto& w : setup.warnings) o << "  " << w << "\n";
  return o.str();
}

template std::string run_header<2>(const CaseSpec&, const CaseSetup<2>&, int);
template std::string run_header<3>(const CaseSpec&, const CaseSetup<3>&, int);

}  // namespace swell
