#include "apps/probe_command.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "case/reader.hpp"
#include "io/gauge_csv.hpp"
#include "io/hdf5_file.hpp"
#include "io/provenance.hpp"
#include "io/vtk_writer.hpp"
#include "run/gauge_set.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

std::string find_run_file(const std::string& dir) {
  if (!fs::is_directory(dir))
    throw std::invalid_argument(dir + ": not a folder (expected a run's output folder)");
  std::string found;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() != ".h5" || name.rfind("checkpoint", 0) == 0) continue;
    if (!found.empty())
      throw std::invalid_argument(dir + ": more than one run file (" + found + ", " + name + ")");
    found = e.path().string();
  }
  if (found.empty())
    throw std::invalid_argument(
        dir + ": no <case>.h5 run file (was the run made with output.hdf5: false?)");
  return found;
}

template <int D>
int probe_dim(const ProbeOptions& opt, const std::string& path, const RunMetadata& meta,
              std::ostream& out) {
  GaugeSpec g;
  g.name = "probe";
  g.at = opt.at;
  if (opt.size && opt.kind != "pressure")
    throw std::invalid_argument("--size is for --kind pressure (a sensor face)");
  if (opt.kind == "pressure") {
    g.kind = GaugeSpec::Kind::Pressure;
    if (opt.normal) g.normal = opt.normal->normalized();
    g.offset = opt.offset;
    if (opt.size) {  // a sensor face, as a case's `size` (needs `normal`)
      if (!opt.normal) throw std::invalid_argument("--size (a sensor face) needs --normal");
      if (!(*opt.size > 0.0)) throw std::invalid_argument("--size: expected a length > 0 [m]");
      g.size = opt.size;
    }
  } else if (opt.kind == "velocity") {
    g.kind = GaugeSpec::Kind::Velocity;
  } else if (opt.kind == "height") {
    g.kind = GaugeSpec::Kind::Height;
  } else if (opt.kind == "runup") {
    g.kind = GaugeSpec::Kind::Runup;
    if (!opt.to) throw std::invalid_argument("--kind runup needs --to (the line's upper end)");
    g.from = opt.at;
    g.to = *opt.to;
    g.swl = opt.swl;
    if (!(g.to[D - 1] > g.from[D - 1]))
      throw std::invalid_argument("--to must lie above --at (the line runs up the slope)");
  } else {
    throw std::invalid_argument("--kind " + opt.kind +
                                ": expected pressure, velocity, height or runup");
  }
  GaugeContext ctx;
  ctx.params.kernel = kernel_from_name(meta.kernel);
  ctx.params.h = meta.h;
  ctx.params.dp = meta.dp;
  ctx.params.rho0 = meta.rho0;
  ctx.params.c0 = meta.c0;
  ctx.up_axis = D - 1;
  // Gravity (a sensor face's hydrostatic extrapolation and wetness): the run's case, else
  // 9.81 m/s^2 down the last axis (the axis the height and runup gauges here take as up).
  ctx.params.gravity = Eigen::Vector3d::Zero();
  ctx.params.gravity[D - 1] = -9.81;
  std::string gravity_note;
  try {
    ctx.params.gravity = parse_case_text(meta.case_text, meta.case_file).gravity;
  } catch (const std::exception& e) {  // said in the CSV header, not fatal
    gravity_note = std::string(
                       "# gravity: 9.81 m/s^2 down the last axis (the run's case could "
                       "not be read again: ") +
                   e.what() + ")\n";
  }

  std::ostringstream csv;
  csv << "# swell probe of " << path << " (case " << meta.case_name << ")\n"
      << provenance_text(capture_provenance(), "# ") << gravity_note;
  csv << "time [s]";
  for (const auto& c : gauge_columns(g, D)) csv << ',' << c;
  csv << '\n';
  int rows = 0;
  const std::vector<Vec<D>> no_ace;
  for (const auto& info : list_snapshots(path)) {
    const SnapshotData<D> s = read_snapshot<D>(path, info);
    ParticleSet<D> ps;
    ps.reserve(s.pos.size());
    double top = -1e300;
    for (std::size_t i = 0; i < s.pos.size(); ++i) {
      ps.add(s.pos[i], s.vel[i], s.rho[i], s.mass[i], static_cast<Role>(s.type[i]), s.body[i]);
      ps.id[i] = s.id[i];
      top = std::max(top, s.pos[i][D - 1]);
    }
    ctx.line_top = top + 2.0 * meta.h;
    const auto values = evaluate_gauge<D>(g, ctx, ps, s.p, no_ace);
    char buf[40];
    format_gauge_time(buf, sizeof(buf), s.time);  // as the run's gauge files
    csv << buf;
    for (double v : values) {
      std::snprintf(buf, sizeof(buf), "%.9g", v);
      csv << ',' << buf;
    }
    csv << '\n';
    ++rows;
  }
  if (opt.output.empty()) {
    out << csv.str();
  } else {
    write_file_atomically(opt.output, csv.str());
  }
  return rows;
}

}  // namespace

Eigen::Vector3d parse_vector_option(const std::string& text, const std::string& option) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  std::stringstream ss(text);
  std::string item;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    if (n == 3) throw std::invalid_argument(option + " " + text + ": expected x,y or x,y,z");
    try {
      std::size_t used = 0;
      v[n] = std::stod(item, &used);
      if (used != item.size()) throw std::invalid_argument("trailing characters");
    } catch (const std::exception&) {
      throw std::invalid_argument(option + " " + text + ": '" + item + "' is not a number");
    }
    ++n;
  }
  if (n < 2) throw std::invalid_argument(option + " " + text + ": expected x,y or x,y,z");
  return v;
}

int run_probe(const ProbeOptions& opt, std::ostream& out) {
  if (!opt.output.empty()) require_output_folder(opt.output, "-o");
  const std::string path = find_run_file(opt.out_dir);
  const RunMetadata meta = read_metadata(path);
  if (meta.dim == 2) return probe_dim<2>(opt, path, meta, out);
  if (meta.dim == 3) return probe_dim<3>(opt, path, meta, out);
  throw std::runtime_error(path + ": metadata dim must be 2 or 3");
}

Subcommand add_probe_command(CLI::App& app) {
  struct Options {
    std::string dir, at, normal, kind = "pressure", out, to;
    double offset = -1.0;
    std::optional<double> swl, size;
  };
  auto o = std::make_shared<Options>();
  auto* probe = app.add_subcommand("probe", "evaluate a gauge on the snapshots of a finished run");
  probe->add_option("outdir", o->dir, "output folder of a run (holding <case>.h5)")->required();
  probe
      ->add_option("--at", o->at,
                   "point x,y[,z] (height: horizontal position and line start; runup: the "
                   "line's lower end on the slope)")
      ->required();
  probe->add_option("--kind", o->kind, "pressure | velocity | height | runup")
      ->check(CLI::IsMember({"pressure", "velocity", "height", "runup"}));
  probe->add_option("--to", o->to, "runup: the line's upper end on the slope x,y[,z]");
  probe->add_option("--swl", o->swl, "runup: still-water level (the value is relative to it)");
  probe->add_option("--normal", o->normal,
                    "pressure: wall normal nx,ny[,nz]; sample at at + offset*normal");
  probe->add_option("--offset", o->offset, "distance along the normal (default h)");
  probe->add_option("--size", o->size,
                    "pressure: a sensor face of this diameter (3D) / length (2D) [m] on the wall "
                    "at --at, needs --normal (the face average, as a case gauge's size)");
  probe->add_option("-o,--out", o->out, "CSV file (default: standard output)");
  return Subcommand(probe, [o] {
    ProbeOptions opt;
    opt.out_dir = o->dir;
    opt.kind = o->kind;
    opt.at = parse_vector_option(o->at, "--at");
    if (!o->normal.empty()) opt.normal = parse_vector_option(o->normal, "--normal");
    if (o->offset >= 0.0) {
      if (!opt.normal) throw std::invalid_argument("--offset needs --normal");
      opt.offset = o->offset;
    }
    if (!o->to.empty()) opt.to = parse_vector_option(o->to, "--to");
    opt.swl = o->swl;
    opt.size = o->size;
    opt.output = o->out;
    const int rows = run_probe(opt, std::cout);
    if (!o->out.empty()) std::cerr << "probe: " << rows << " snapshots -> " << o->out << "\n";
    return 0;
  });
}

}  // namespace swell
