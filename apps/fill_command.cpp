#include "apps/fill_command.hpp"

#include <omp.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "case/geometry.hpp"
#include "case/reader.hpp"
#include "case/setup.hpp"
#include "geometry/fill_volume.hpp"
#include "io/provenance.hpp"
#include "io/vtk_writer.hpp"
#include "solver/physics/eos.hpp"

namespace swell {
namespace {

std::string percent(double fraction) {
  std::ostringstream s;
  s << std::showpos << std::fixed << std::setprecision(3) << std::round(1e5 * fraction) / 1e3 + 0.0
    << " %";
  return s.str();
}

// fill_info.yaml: what `swell fill` made, and how.
void write_fill_info(const std::string& path, const CaseSpec& spec, const FillSummary& sum,
                     const Provenance& prov) {
  std::ostringstream o;
  o << std::setprecision(10);
  const char* unit = spec.dim == 2 ? "m^2" : "m^3";
  o << "# what swell fill made of " << spec.file << ", and how (volumes in " << unit << ")\n"
    << "kind: fill\ncase: \"" << spec.file << "\"\ndp: " << spec.dp << "\n"
    << "particles: " << sum.fluid + sum.boundary << "\nfluid: " << sum.fluid
    << "\nboundary: " << sum.boundary << "\nvtp: \"" << sum.vtp << "\"\n";
  if (!sum.volumes.empty()) o << "volumes:\n";
  for (const auto& v : sum.volumes) {
    o << "  - {body: \"" << v.body << "\", particles: " << v.particles;
    if (std::isfinite(v.region))
      o << ", region: " << v.region << ", structures: " << v.structures << ", water: " << v.water()
        << ", void: " << v.void_volume();
    if (v.spacing > 0.0) o << ", counted_on: " << v.spacing;
    o << "}\n";
  }
  o << "provenance:\n";
  std::string block = provenance_yaml(prov, 4);
  block.replace(0, 4, "  - ");
  o << block;
  write_file_atomically(path, o.str());
}

template <int D>
FillSummary fill_dim(const CaseSpec& spec, const FillCommandOptions& opt, std::ostream& log) {
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const Provenance prov = capture_provenance();
  const std::filesystem::path out(opt.out_dir.empty() ? "out/" + spec.name : opt.out_dir);
  const CaseSetup<D> setup = setup_case<D>(spec);

  FillSummary sum;
  for (const auto& b : setup.bodies) (b.fluid ? sum.fluid : sum.boundary) += b.particles;
  sum.fill_seconds = setup.fill_seconds;

  // The structures' part of each fluid region, on a lattice dp/8 (2D) or dp/4 (3D) apart.
  {
    const std::vector<geometry::BodyGeometry> bodies = case_geometry(spec);
    const double cell = std::pow(spec.dp, D);
    for (std::size_t i = 0; i < setup.fill.size() && i < bodies.size(); ++i) {
      const geometry::BodyFillReport& r = setup.fill[i];
      if (!r.fluid) continue;
      FluidVolumeCheck v;
      v.body = r.name;
      v.particles = static_cast<double>(r.particles) * cell;
      v.lattice = static_cast<double>(r.in_region) * cell;
      v.region = r.region_volume;
      const geometry::StructureOverlap o =
          geometry::structures_in_region(bodies, i, D, spec.dp, D == 2 ? 8 : 4);
      v.structures = o.volume;
      v.spacing = o.spacing;
      sum.volumes.push_back(v);
    }
  }

  log << "fill " << spec.name << " (" << spec.file << "): " << D << "D, dp = " << spec.dp << " m, "
      << omp_get_max_threads() << " thread(s)\n";
  print_fill_report(log, setup.fill, setup.meshes, D, spec.dp, setup.fill_seconds, &sum.volumes);
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
  write_vtp<D>(sum.vtp, setup.particles, pressure, ParticleFilter::All, &names, 0.0);
  sum.info = (out / "fill_info.yaml").string();
  write_fill_info(sum.info, spec, sum, prov);
  log << "  written:   " << sum.vtp << ", " << sum.info << "\n";
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
                       double fill_seconds, const std::vector<FluidVolumeCheck>* volumes) {
  std::ostringstream s;
  s << std::setprecision(6);
  for (const auto& m : meshes) s << mesh_line(m);
  std::size_t fluid = 0, boundary = 0;
  const char* unit = dim == 2 ? " m^2" : " m^3";
  std::size_t fluid_index = 0;
  for (const auto& b : bodies) {
    (b.fluid ? fluid : boundary) += b.particles;
    s << "  body " << b.name << " (" << (b.fluid ? "fluid" : "boundary") << ", " << b.region
      << "): " << b.particles << " particles\n";
    if (!b.fluid) continue;
    const FluidVolumeCheck* v =
        volumes && fluid_index < volumes->size() ? &(*volumes)[fluid_index] : nullptr;
    ++fluid_index;
    const double lattice = static_cast<double>(b.in_region) * std::pow(dp, dim);
    if (v && v->spacing > 0.0 && std::isfinite(v->region)) {
      // Structures in the region: the particles against the water, region less structures.
      s << "    volume: N dp^" << dim << " = " << v->particles << unit << " (the fluid particles);"
        << " water = region " << v->region << unit << " - structures " << v->structures << unit
        << " = " << v->water() << unit << " (" << percent(v->particles / v->water() - 1.0) << ")\n"
        << "    void:   " << v->void_volume() << unit
        << " of the water holds no particle (lattice steps along sloping or curved structure "
           "faces, dp/2 gaps at walls); structures counted on a "
        << v->spacing << " m lattice\n"
        << "    lattice before structures are cut out: " << lattice << unit << " ("
        << percent(b.volume_error(dim, dp)) << " of the region)\n";
      continue;
    }
    s << "    volume: N dp^" << dim << " = " << lattice << unit;
    if (std::isfinite(b.region_volume))
      s << ", region " << b.region_volume << unit << " (" << percent(b.volume_error(dim, dp))
        << ")";
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

Subcommand add_fill_command(CLI::App& app) {
  struct Options {
    std::string case_path;
    std::vector<std::string> sets;
    FillCommandOptions fill;
  };
  auto o = std::make_shared<Options>();
  auto* fill = app.add_subcommand(
      "fill", "build a case's particles as `run` would, write <name>_fill.vtp and report");
  fill->add_option("case", o->case_path, "case file (YAML)")->required();
  add_set_option(fill, o->sets);
  fill->add_option("-o,--out", o->fill.out_dir, "output folder (default: out/<case name>)");
  fill->add_option("-t,--threads", o->fill.threads, "OpenMP threads (default: all cores)")
      ->check(count_check());
  return Subcommand(fill, [o] {
    run_fill(load_case_file(o->case_path, o->sets), o->fill, std::cout);
    return 0;
  });
}

}  // namespace swell
