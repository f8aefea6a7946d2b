// `swell foam`, part 1: from a CaseSpec to the mesh and sampling plan (make_plan).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "case/geometry.hpp"
#include "foam/foam.hpp"
#include "foam/plan.hpp"
#include "waves/dispersion.hpp"
#include "waves/wavemaker.hpp"

namespace swell::foam {

const char* const kFaceNames[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};

Eigen::Vector3d Grid::centre(long c) const {
  const long i = c % n[0], j = (c / n[0]) % n[1], k = c / (static_cast<long>(n[0]) * n[1]);
  return {min[0] + (static_cast<double>(i) + 0.5) * cell[0],
          min[1] + (static_cast<double>(j) + 0.5) * cell[1],
          min[2] + (static_cast<double>(k) + 0.5) * cell[2]};
}

Eigen::Vector3i Grid::locate(const Eigen::Vector3d& x) const {
  Eigen::Vector3i ijk;
  for (int d = 0; d < 3; ++d) {
    const long v = static_cast<long>(std::floor((x[d] - min[d]) / cell[d]));
    ijk[d] = static_cast<int>(std::clamp<long>(v, 0, n[d] - 1));
  }
  return ijk;
}

double gauge_interval(const CaseSpec& spec, const GaugeSpec& g) {
  if (g.every > 0.0) return g.every;
  if (spec.gauge_every > 0.0) return spec.gauge_every;
  const double every = spec.output_every > 0.0 ? spec.output_every : spec.t_end;
  return every / 10.0;
}

std::string foam_word(const std::string& s) {
  std::string w;
  for (char c : s) w += (std::isalnum(static_cast<unsigned char>(c)) || c == '_') ? c : '_';
  if (w.empty() || std::isdigit(static_cast<unsigned char>(w[0]))) w = "g_" + w;
  return w;
}

namespace {

bool inside_grid(const Grid& g, const Eigen::Vector3d& x) {
  for (int d = 0; d < g.dim; ++d)
    if (x[d] < g.min[d] || x[d] > g.max[d]) return false;
  return true;
}

// A sampling point lying on a cell face would be found in either neighbouring cell, depending
// on round-off; move it a hair (1e-4 cell) towards +axis so the choice is deterministic.
Eigen::Vector3d off_faces(const Grid& g, Eigen::Vector3d x, int skip_axis = -1) {
  for (int d = 0; d < g.dim; ++d) {
    if (d == skip_axis) continue;
    const double t = (x[d] - g.min[d]) / g.cell[d];
    if (std::abs(t - std::round(t)) < 1e-6) x[d] += 1e-4 * g.cell[d];
  }
  return x;
}

bool removed_at(const Plan& p, const Eigen::Vector3d& x) {
  const Eigen::Vector3i c = p.grid.locate(x);
  return p.removed[p.grid.index(c[0], c[1], c[2])] != 0;
}

// Cells of the grid whose centre satisfies `inside`, visiting only those in [lo, hi].
template <class Inside>
void for_cells_in(const Grid& g, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                  Inside&& inside) {
  const Eigen::Vector3i a = g.locate(lo), b = g.locate(hi);
  for (int k = a[2]; k <= b[2]; ++k)
    for (int j = a[1]; j <= b[1]; ++j)
      for (int i = a[0]; i <= b[0]; ++i) {
        const long c = g.index(i, j, k);
        inside(c, g.centre(c));
      }
}

// The wave paddle, if any: checks that interFoam's waveModels can make its wave and fills
// p.wave, p.time_offset and p.z_up. Returns the paddle's body index (bodies.size() if none).
// Bodies with any other motion are refused: the mesh here cannot move.
std::size_t plan_wave(const CaseSpec& spec, const std::vector<geometry::BodyGeometry>& geo,
                      const BodySpec& tank, Plan& p) {
  std::size_t paddle = spec.bodies.size();
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    const BodySpec& b = spec.bodies[i];
    const MotionSpec& m = b.motion;
    if (m.type == MotionSpec::Type::None) continue;
    const std::string where = spec.file + ": body " + b.name + ", motion: ";
    if (m.type != MotionSpec::Type::Wave)
      throw std::invalid_argument(
          where + "swell foam cannot map a " +
          (m.type == MotionSpec::Type::File ? std::string("motion from a file (type: file)")
                                            : std::string("prescribed motion")) +
          "; interFoam runs only fixed Cartesian meshes here, so only a piston wave paddle "
          "(type: wave, paddle: piston) is mapped, to a wave inlet");
    if (paddle != spec.bodies.size())
      throw std::invalid_argument(where + "swell foam maps one wave paddle; " +
                                  spec.bodies[paddle].name + " is one already");
    if (!m.paddle || m.paddle->paddle.type != waves::PaddleGeometry::Type::Piston)
      throw std::invalid_argument(where +
                                  "paddle: flap cannot be mapped (interFoam's waveModels make "
                                  "the wave at a fixed inlet as a piston's far field); use "
                                  "paddle: piston");
    if (m.wave_kind != "regular" && m.wave_kind != "solitary")
      throw std::invalid_argument(where + "wave: " + m.wave_kind +
                                  " cannot be mapped (swell foam maps wave: regular, order 1 "
                                  "or 2, and wave: solitary)");
    if (!(m.direction[0] > 1.0 - 1e-9))
      throw std::invalid_argument(where +
                                  "direction: swell foam needs waves travelling along +x "
                                  "(the paddle at the tank's xmin end)");
    if (std::isfinite(m.stop) && m.stop < spec.t_end)
      throw std::invalid_argument(where +
                                  "stop: interFoam's waveModels cannot stop a wave; remove "
                                  "`stop` or end the case before it");
    paddle = i;
    WaveInlet& w = p.wave;
    w.present = true;
    w.body = b.name;
    w.x0 = geo[i].shape->bounds().max[0];  // the fluid-side face at rest
    if (!(w.x0 > tank.shape.box.min[0] && w.x0 < tank.shape.box.max[0]))
      throw std::invalid_argument(where + "the paddle's face (x = " + std::to_string(w.x0) +
                                  ") must lie inside the tank");
    w.height = m.wave_height;
    w.depth = m.paddle->paddle.depth;
    p.time_offset = m.start;
    const double g = spec.gravity.norm();
    if (m.wave_kind == "regular") {
      w.model = m.wave_order == 2 ? "StokesII" : "StokesI";
      w.period = m.wave_period;
      w.ramp = m.ramp;
      // The SPH paddle makes eta(x, tau) = a cos(w tau + phi - k x) (+ the bound 2nd harmonic
      // at twice the phase), x from its rest face, tau = t - start (waves/wavemaker.hpp).
      // waveModels impose eta = a cos(k x_in - w t + wavePhase) at the inlet x_in = x0; with
      // OpenFOAM t = tau: wavePhase = -(phi + k x0), wrapped to [0, 2 pi).
      const double omega = 2.0 * M_PI / w.period;
      const double k = waves::wave_number(omega, w.depth, g);
      w.phase = std::fmod(-(m.wave_phase + k * w.x0), 2.0 * M_PI);
      if (w.phase < 0.0) w.phase += 2.0 * M_PI;
    } else {
      // 1912's solitary model `Boussinesq` puts the crest at the inlet at t_in = 3.5 d
      // sqrt(d / H) / c, c = sqrt(g (d + H)). Goring's paddle (waves/wavemaker.hpp) makes
      // eta = H sech^2(kappa (c (tau - t0) - X)), t0 = duration / 2, X from the trajectory's
      // middle; its rest face is X = X(0) = soliton.start (~ -S/2), reached by the crest at
      // tau = t0 + start / c. OpenFOAM t = 0 is case time start + t0 + start / c - t_in.
      w.model = "Boussinesq";
      const waves::SolitaryPaddle& s = m.paddle->soliton;
      const double c = std::sqrt(g * (w.depth + w.height));
      const double t_in = 3.5 * w.depth * std::sqrt(w.depth / w.height) / c;
      p.time_offset += 0.5 * s.duration + s.start / s.celerity - t_in;
      if (p.time_offset < 0.0)
        throw std::invalid_argument(where + "start: give the solitary wave " +
                                    std::to_string(-p.time_offset) +
                                    " s more start time for interFoam's solitary model");
    }
    w.absorbing_outlet = !spec.damping.empty();
    p.notes.push_back(
        "wave paddle " + b.name + " -> inlet (" + w.model + ") at x = " + std::to_string(w.x0) +
        " m; far end: " + (w.absorbing_outlet ? "outlet (shallowWaterAbsorption)" : "wall") +
        (p.time_offset != 0.0
             ? "; OpenFOAM t = 0 is case time " + std::to_string(p.time_offset) + " s"
             : std::string()));
    if (m.absorption)
      p.notes.push_back("wave paddle " + b.name +
                        ": its active absorption (absorption:) is not mapped as such; the "
                        "waveModels inlet absorbs with its own shallow-water correction "
                        "(activeAbsorption yes, Higuera et al. 2013), not the paddle's "
                        "Schaffer-Klopman gain, filter and drift");
  }
  p.z_up = paddle != spec.bodies.size() && spec.dim == 2;
  return paddle;
}

}  // namespace

Plan make_plan(const CaseSpec& spec, const FoamOptions& opt) {
  Plan p;
  p.case_name = spec.name;
  const int dim = spec.dim;
  Grid& g = p.grid;
  g.dim = dim;
  g.up = dim - 1;

  // The tank: the first boundary body with inside walls and a box shape.
  const BodySpec* tank = nullptr;
  std::size_t tank_index = 0;
  for (std::size_t i = 0; i < spec.bodies.size() && !tank; ++i) {
    const BodySpec& b = spec.bodies[i];
    if (b.kind == BodySpec::Kind::Boundary && b.walls == BodySpec::Walls::Inside &&
        b.shape.type == ShapeSpec::Type::Box) {
      tank = &b;
      tank_index = i;
    }
  }
  if (spec.periodic[0] || spec.periodic[1] || spec.periodic[2])
    throw std::invalid_argument(spec.file +
                                ": domain.periodic: swell foam does not write periodic (cyclic) "
                                "patches; remove domain.periodic for the OpenFOAM case");
  if (!tank)
    throw std::invalid_argument(spec.file +
                                ": swell foam needs a box tank (a boundary body with "
                                "`walls: inside` and a box shape); the OpenFOAM mesh spans it");
  p.tank = tank->name;
  p.open = tank->open;
  // Every body's shape, and each fill's container, as the SPH fill sees them.
  const std::vector<geometry::BodyGeometry> geo = case_geometry(spec);
  const std::size_t paddle_index = plan_wave(spec, geo, *tank, p);

  const double cell = opt.cell_size > 0.0 ? opt.cell_size : spec.dp / opt.cells_per_dp;
  if (!(cell > 0.0) || !std::isfinite(cell))
    throw std::invalid_argument("swell foam: the cell size must be > 0 (--cell or --cells-per-dp)");
  p.cell_size = cell;
  g.min = tank->shape.box.min;
  g.max = tank->shape.box.max;
  if (p.wave.present) g.min[0] = p.wave.x0;  // the mesh starts at the paddle's face
  for (int d = 0; d < dim; ++d) {
    const double len = g.max[d] - g.min[d];
    if (!(len > 0.0)) throw std::invalid_argument(spec.file + ": the tank box is empty");
    g.n[d] = std::max(1, static_cast<int>(std::lround(len / cell)));
    g.cell[d] = len / g.n[d];
  }
  if (dim == 2) {  // one cell thick, centred on the SPH plane z = 0
    g.min[2] = -0.5 * cell;
    g.max[2] = 0.5 * cell;
    g.n[2] = 1;
    g.cell[2] = cell;
  }
  if (g.count() > 50'000'000L)
    throw std::invalid_argument("swell foam: " + std::to_string(g.count()) +
                                " cells is too many; choose a larger --cell");

  p.end_time = (opt.end_time >= 0.0 ? opt.end_time : spec.t_end) - p.time_offset;
  if (!(p.end_time > 0.0))
    throw std::invalid_argument("swell foam: the end time must be > 0" +
                                (p.time_offset > 0.0 ? " and after the wave's start (" +
                                                           std::to_string(p.time_offset) + " s)"
                                                     : std::string()));
  p.write_interval = p.end_time / 10.0;
  p.rho_water = spec.rho0;
  p.gravity = spec.gravity;
  if (dim == 2) p.gravity[2] = 0.0;
  // Boxes given to topoSet/setFields (boxToCell: cells whose centre lies in the box, faces
  // included) are shrunk by 1e-6 cell, so a centre lying exactly on a box face is out on both
  // sides (here and in OpenFOAM) whatever the round-off.
  const double eps = 1e-6 * cell;
  auto box_lo = [&](const Eigen::Vector3d& v) {
    Eigen::Vector3d r = v.array() + eps;
    if (dim == 2) r[2] = -1.0;
    return r;
  };
  auto box_hi = [&](const Eigen::Vector3d& v) {
    Eigen::Vector3d r = v.array() - eps;
    if (dim == 2) r[2] = 1.0;
    return r;
  };
  auto in_box = [](const Eigen::Vector3d& x, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
  };

  // Obstacles: cells whose centre lies inside the structure are cut out, body by body.
  p.removed.assign(static_cast<std::size_t>(g.count()), 0);
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    const BodySpec& b = spec.bodies[i];
    if (b.kind != BodySpec::Kind::Boundary || i == tank_index || i == paddle_index) continue;
    if (b.walls == BodySpec::Walls::Inside) {
      p.notes.push_back("body " + b.name +
                        ": a second `walls: inside` body is not meshed (only the tank is)");
      continue;
    }
    Obstacle ob;
    ob.name = foam_word(b.name);
    const geometry::ShapePtr& shape = geo[i].shape;
    const auto bb = shape->bounds();
    Eigen::Vector3d lo = bb.min, hi = bb.max;
    if (dim == 2) lo[2] = hi[2] = 0.0;
    if (b.shape.type == ShapeSpec::Type::Box) {
      ob.is_box = true;
      ob.box_min = box_lo(b.shape.box.min);
      ob.box_max = box_hi(b.shape.box.max);
    }
    for_cells_in(g, lo, hi, [&](long c, const Eigen::Vector3d& x) {
      if (p.removed[c]) return;
      const bool in = ob.is_box ? in_box(x, ob.box_min, ob.box_max) : shape->contains(x);
      if (in) ob.cells.push_back(c);
    });
    std::sort(ob.cells.begin(), ob.cells.end());
    if (ob.cells.empty()) {
      p.notes.push_back("body " + b.name + ": no cell centre inside it at this cell size; not cut");
      continue;
    }
    // Labels in the mesh left by the previous cuts: subsetMesh keeps cells in their order.
    std::vector<long> rank(static_cast<std::size_t>(g.count()));
    long r = 0;
    for (long c = 0; c < g.count(); ++c) {
      rank[c] = r;
      if (!p.removed[c]) ++r;
    }
    for (long c : ob.cells) ob.labels.push_back(rank[c]);
    for (long c : ob.cells) p.removed[c] = 1;
    p.obstacles.push_back(std::move(ob));
  }
  p.kept_cells = g.count() - static_cast<long>(std::count(p.removed.begin(), p.removed.end(), 1));

  // Water: boxes (and fills of the box tank) through setFields; other shapes cell by cell.
  p.wet.assign(static_cast<std::size_t>(g.count()), 0);
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    const BodySpec& b = spec.bodies[i];
    if (b.kind != BodySpec::Kind::Fluid) continue;
    if (b.fill_below) {
      const auto host = static_cast<std::size_t>(geo[i].container);
      const double level = *b.fill_below;
      if (host == tank_index) {
        Eigen::Vector3d top = tank->shape.box.max;
        top[g.up] = level;
        const FluidBox fb{b.name, box_lo(tank->shape.box.min), box_hi(top)};
        p.fluid_boxes.push_back(fb);
        for (long c = 0; c < g.count(); ++c)
          if (in_box(g.centre(c), fb.min, fb.max)) p.wet[c] = 1;
      } else {
        const geometry::ShapePtr& shape = geo[host].shape;
        p.alpha_by_list = true;
        for (long c = 0; c < g.count(); ++c) {
          const Eigen::Vector3d x = g.centre(c);
          if (x[g.up] < level && shape->contains(x)) p.wet[c] = 1;
        }
      }
    } else if (b.shape.type == ShapeSpec::Type::Box) {
      FluidBox fb{b.name, box_lo(b.shape.box.min), box_hi(b.shape.box.max)};
      // SPH water starts a particle gap or so off the paddle; the inlet needs it at its face.
      const double gap = fb.min[0] - g.min[0];
      if (p.wave.present && gap > 0.0 && gap < 3.0 * spec.dp) {
        fb.min[0] = g.min[0];
        p.notes.push_back("fluid body " + b.name + ": starts " + std::to_string(gap) +
                          " m off the paddle face; extended to the inlet");
      }
      p.fluid_boxes.push_back(fb);
      for (long c = 0; c < g.count(); ++c)
        if (in_box(g.centre(c), fb.min, fb.max)) p.wet[c] = 1;
    } else {
      const geometry::ShapePtr& shape = geo[i].shape;
      p.alpha_by_list = true;
      for (long c = 0; c < g.count(); ++c)
        if (shape->contains(g.centre(c))) p.wet[c] = 1;
    }
  }
  for (long c = 0; c < g.count(); ++c)
    if (p.removed[c]) p.wet[c] = 0;

  // Gauges.
  double floor = std::numeric_limits<double>::infinity();
  for (long c = 0; c < g.count(); ++c)
    if (p.wet[c]) floor = std::min(floor, g.centre(c)[g.up] - 0.5 * g.cell[g.up]);
  std::map<std::pair<int, double>, int> groups;  // (kind, every) -> function object number
  for (const auto& gs : spec.gauges) {
    Probe pr;
    pr.spec = gs;
    pr.every = gauge_interval(spec, gs);
    auto skip = [&](const std::string& why) {
      pr.skipped = true;
      p.notes.push_back("gauge " + gs.name + ": " + why + "; not sampled");
    };
    Eigen::Vector3d at = gs.at;
    if (dim == 2) at[2] = 0.0;
    switch (gs.kind) {
      case GaugeSpec::Kind::Pressure:
      case GaugeSpec::Kind::Velocity: {
        Eigen::Vector3d x = at;
        if (gs.kind == GaugeSpec::Kind::Pressure && gs.normal && gs.normal->head(dim).norm() > 0) {
          // The first cell centre off the wall along the normal (the wall lies on a cell face
          // for grid-aligned walls): at + (cell/2) n, further out while that cell is cut away.
          Eigen::Vector3d n = Eigen::Vector3d::Zero();
          n.head(dim) = gs.normal->head(dim).normalized();
          double cn = 0.0;
          for (int d = 0; d < dim; ++d) cn += std::abs(n[d]) * g.cell[d];
          x = at + 0.5 * cn * n;
          for (int step = 0; step < 4 && inside_grid(g, x) && removed_at(p, x); ++step) x += cn * n;
        }
        x = off_faces(g, x);
        if (!inside_grid(g, x)) {
          skip("the point lies outside the tank");
        } else if (removed_at(p, x)) {
          skip("the point lies inside a solid body");
        }
        pr.point = x;
        break;
      }
      case GaugeSpec::Kind::Height: {
        Eigen::Vector3d s = off_faces(g, at, g.up);
        s[g.up] = std::max(s[g.up], g.min[g.up]);
        Eigen::Vector3d e = s;
        e[g.up] = g.max[g.up];
        pr.start = s;
        pr.end = e;
        pr.points = 4 * static_cast<int>(std::ceil((e[g.up] - s[g.up]) / g.cell[g.up])) + 1;
        if (!(e[g.up] > s[g.up]) || !inside_grid(g, s)) skip("the line lies outside the tank");
        break;
      }
      case GaugeSpec::Kind::Front: {
        if (!std::isfinite(floor)) {
          skip("no water at the start");
          break;
        }
        pr.level = floor;
        const double row = floor + 0.5 * g.cell[g.up];
        std::vector<double> laterals{0.0};
        if (dim == 3) {  // a few lines across the tank; the front is the furthest
          laterals.clear();
          const int ny = g.n[1], lines = std::min(ny, 5);
          for (int k = 0; k < lines; ++k) {
            const int j = std::clamp(static_cast<int>((k + 0.5) * ny / lines), 0, ny - 1);
            laterals.push_back(g.min[1] + (j + 0.5) * g.cell[1]);
          }
          laterals.erase(std::unique(laterals.begin(), laterals.end()), laterals.end());
        }
        for (double y : laterals) {
          Eigen::Vector3d s = Eigen::Vector3d::Zero(), e = Eigen::Vector3d::Zero();
          s[0] = g.min[0] + 0.5 * g.cell[0];
          e[0] = g.max[0] - 0.5 * g.cell[0];
          if (dim == 3) s[1] = e[1] = y;
          s[g.up] = e[g.up] = row;
          pr.line_starts.push_back(s);
          pr.line_ends.push_back(e);
        }
        pr.points = g.n[0];
        break;
      }
      case GaugeSpec::Kind::Force: {
        if (gs.body == tank->name) {
          pr.patches.push_back("tank");
        } else {
          for (const auto& ob : p.obstacles)
            if (ob.name == foam_word(gs.body)) pr.patches.push_back(ob.name);
        }
        if (pr.patches.empty()) skip("body " + gs.body + " has no wall patch in the mesh");
        if (gs.moment_about) pr.cofr = *gs.moment_about;
        break;
      }
      case GaugeSpec::Kind::Runup:
        skip("swell foam does not sample runup gauges");
        break;
    }
    if (gs.kind == GaugeSpec::Kind::Force) {
      pr.function = "force_" + foam_word(gs.name);
    } else {
      const auto key = std::make_pair(static_cast<int>(gs.kind), pr.every);
      if (!groups.count(key)) {
        int n = 0;
        for (const auto& [k, v] : groups)
          if (k.first == key.first) ++n;
        groups[key] = n;
      }
      pr.function = std::string(gauge_kind_name(gs.kind)) + "_" + std::to_string(groups[key]);
    }
    p.probes.push_back(pr);
  }
  return p;
}

}  // namespace swell::foam
