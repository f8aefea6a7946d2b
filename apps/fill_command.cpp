#include "apps/fill_command.hpp"

#include <omp.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "io/case_setup.hpp"
#include "io/vtk_writer.hpp"
#include "solver/physics/eos.hpp"

namespace swell {
namespace {

template <int D>
FillSummary fill_dim(const CaseSpec& spec, const FillCommandOptions& opt, std::ostream& log) {
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const std::filesystem::path out(opt.out_dir.empty() ? "out/" + spec.name : opt.out_dir);
  const CaseSetup<D> setup = setup_case<D>(spec);

  FillSummary sum;
  for (const auto& b : setup.bodies) (b.fluid ? sum.fluid : sum.boundary) += b.particles;
  sum.fill_seconds = setup.fill_seconds;

  log << "fill " << spec.name << " (" << spec.file << "): " << D << "D, dp = " << spec.dp << " m, "
      << omp_get_max_threads() << " thread(s)\n";
  print_fill_report(log, setup.fill, setup.meshes, D, spec.dp, setup.fill_seconds);
  for (const auto& w : setup.warnings) log << "  " << w << "\n";

  // Initial state as the run starts it: hydrostatic densities and their EoS pressure.
  const SolverParams& p = setup.params;
  const TaitEos eos(p.rho0, p.c0, p.gamma);
  std::vector<double> pressure(setup.particles.size());
  for (std::size_t i = 0; i < pressure.size(); ++i)
    pressure[i] = eos.pressure(setup.particles.rho[i]);
  std::vector<std::string> names;
  for (const auto& b : setup.bodies) names.push_back(b.name);
  std::filesystem::create_directories(out);
  sum.vtp = (out / (spec.name + "_fill.vtp")).string();
  write_vtp<D>(sum.vtp, setup.particles, pressure, ParticleFilter::All, &names);
  log << "  written:   " << sum.vtp << "\n";
  return sum;
}

std::string mesh_line(const geometry::MeshReport& m) {
  std::ostringstream s;
  s << "  mesh " << m.file << ": " << m.faces << " faces, " << m.vertices << " vertices, "
    << (m.closed ? "closed" : "open") << ", volume " << m.volume << " m^3";
  if (m.border_edges) s << ", " << m.border_edges << " border edges before repair";
  if (m.self_intersections)
    s << ", " << m.self_intersections << " self-intersecting face pairs before repair";
  if (m.reoriented) s << ", normals flipped outward";
  s << "\n";
  for (const auto& r : m.repairs) s << "    repaired: " << r << "\n";
  return s.str();
}

}  // namespace

void print_fill_report(std::ostream& out, const std::vector<geometry::BodyFillReport>& bodies,
                       const std::vector<geometry::MeshReport>& meshes, int dim, double dp,
                       double fill_seconds) {
  std::ostringstream s;
  s << std::setprecision(6);
  for (const auto& m : meshes) s << mesh_line(m);
  std::size_t fluid = 0, boundary = 0;
  const char* unit = dim == 2 ? " m^2" : " m^3";
  for (const auto& b : bodies) {
    (b.fluid ? fluid : boundary) += b.particles;
    s << "  body " << b.name << " (" << (b.fluid ? "fluid" : "boundary") << ", " << b.region
      << "): " << b.particles << " particles\n";
    if (!b.fluid) continue;
    const double lattice = static_cast<double>(b.in_region) * std::pow(dp, dim);
    s << "    volume: N dp^" << dim << " = " << lattice << unit;
    if (std::isfinite(b.region_volume))
      s << ", region " << b.region_volume << unit << " (" << std::showpos << std::fixed
        << std::setprecision(3) << std::round(1e5 * b.volume_error(dim, dp)) / 1e3 + 0.0 << "%)"
        << std::noshowpos << std::defaultfloat << std::setprecision(6);
    else
      s << " (region volume not known exactly)";
    s << "\n";
    if (b.in_region > b.particles)
      s << "    " << b.in_region - b.particles << " of " << b.in_region
        << " region points removed (inside or near walls, or held by an earlier fluid body)\n";
  }
  s << "  total:     " << fluid + boundary << " particles (" << fluid << " fluid, " << boundary
    << " boundary)\n"
    << "  fill time: " << std::setprecision(3) << fill_seconds << " s (shapes, meshes, lattice)\n";
  out << s.str();
}

FillSummary run_fill(const CaseSpec& spec, const FillCommandOptions& opt, std::ostream& log) {
  if (spec.dim == 2) return fill_dim<2>(spec, opt, log);
  if (spec.dim == 3) return fill_dim<3>(spec, opt, log);
  throw std::invalid_argument(spec.file + ": dim must be 2 or 3");
}

}  // namespace swell
