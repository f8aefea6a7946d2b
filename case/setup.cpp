// From a parsed case to particles, parameters and the simulation (case/setup.hpp).
#include "case/setup.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

#include "bc/damping.hpp"
#include "bc/dbc.hpp"
#include "bc/mdbc.hpp"
#include "bc/moving_bodies.hpp"
#include "case/geometry.hpp"
#include "case/reader.hpp"
#include "geometry/lattice_fill.hpp"
#include "geometry/wall_normals.hpp"
#include "solver/time/correction_hooks.hpp"
#include "solver/time/shifting_hook.hpp"

namespace swell {

// Per particle: the state and integrator fields (103 B in 3D), the force buffers (40 B, also
// the sort's scratch), cell ids and sort order (8 B), and what the case's features add. The
// set-up's peak (fill points, hydrostatic sort in place) is below the time loop's.
double bytes_per_particle(const CaseSpec& spec, int dim) {
  // Measured marginal memory of swell run (bench/RESULTS.md, "Memory per particle"): 163 B in
  // 3D and 137 B in 2D with DBC; mDBC's wall vectors +24 B (3D), shifting's work arrays +85 B
  // (3D). Each figure here is ~25 % above the measurement (allocator slack, set-up), and an
  // optional vector field (mDBC normals, moving bodies' reference positions) costs 8 B per
  // component.
  const bool three = dim == 3;
  double b = three ? 205.0 : 175.0;
  bool mdbc = spec.boundary == BoundaryType::Mdbc, moving = false;
  for (const auto& body : spec.bodies) {
    mdbc = mdbc || body.boundary.value_or(spec.boundary) == BoundaryType::Mdbc;
    moving = moving || body.motion.type != MotionSpec::Type::None;
  }
  const double vec = 8.0 * dim * 1.25;
  if (mdbc) b += vec;
  // pos_ref, and normal_ref with mDBC (and wall_acc with its hydrostatic wall pressure)
  if (moving)
    b += vec * (mdbc ? (spec.mdbc_pressure == MdbcPressure::Hydrostatic ? 3.0 : 2.0) : 1.0);
  if (spec.shifting == ShiftingModel::Fickian) b += three ? 105.0 : 80.0;
  return b;
}

// Per grid cell: its start, cursor and fluid flag.
double estimated_bytes(double particles, double grid_cells, double per_particle) {
  return per_particle * particles + 16.0 * grid_cells;
}

double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0.0, pages_resident = 0.0;
  if (!(statm >> pages_total >> pages_resident)) return 0.0;
  const long size = sysconf(_SC_PAGESIZE);
  return size > 0 ? pages_resident * static_cast<double>(size) : 0.0;
}

double available_memory_bytes() {
  double avail = -1.0;
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (meminfo >> key >> kb >> unit) {
    if (key == "MemAvailable:") {
      avail = kb * 1024.0;
      break;
    }
  }
  if (avail < 0.0) {
    const long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    avail = pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 0.0;
  }
  // A container's own limit (cgroup v2, then v1), less what it already uses.
  for (const auto& [limit_file, usage_file] :
       {std::pair<const char*, const char*>{"/sys/fs/cgroup/memory.max",
                                            "/sys/fs/cgroup/memory.current"},
        {"/sys/fs/cgroup/memory/memory.limit_in_bytes",
         "/sys/fs/cgroup/memory/memory.usage_in_bytes"}}) {
    std::ifstream lf(limit_file), uf(usage_file);
    double limit = 0.0, used = 0.0;
    if (lf >> limit && uf >> used && limit > used && limit < 1e18)
      avail = std::min(avail, limit - used);
  }
  return avail;
}

namespace {

std::string bytes_text(double b) {
  std::ostringstream o;
  o << std::setprecision(3);
  if (b >= 1e12)
    o << b / 1e12 << " TB";
  else if (b >= 1e9)
    o << b / 1e9 << " GB";
  else
    o << b / 1e6 << " MB";
  return o.str();
}

// Refuses a case whose particles (upper estimate from the bounds) exceed limits.max_particles
// or whose memory exceeds 80 % of what the machine has available, before anything is filled.
// `node_share`: the fraction of the case this machine holds (a distributed set-up: its ranks'
// shares; 1 otherwise).
void check_size(const CaseSpec& spec, const geometry::FillEstimate& est, int dim,
                double node_share) {
  const double avail = available_memory_bytes();
  const double need = estimated_bytes(est.total * node_share, 0.0, bytes_per_particle(spec, dim));
  const bool too_many = est.total > spec.max_particles;
  const bool too_big = avail > 0.0 && need > 0.8 * avail;
  if (!too_many && !too_big) return;
  std::ostringstream m;
  m << std::setprecision(3) << "the case would make up to " << est.total << " particles (";
  for (std::size_t b = 0; b < est.particles.size() && b < spec.bodies.size(); ++b)
    m << (b ? ", " : "") << "'" << spec.bodies[b].name << "' " << est.particles[b];
  m << ") at dp = " << spec.dp << " m, needing about " << bytes_text(need) << " of memory"
    << (node_share < 1.0 ? " on this machine (its ranks' shares)" : "") << "; ";
  if (too_big) m << "this machine has " << bytes_text(avail) << " available";
  if (too_big && too_many) m << ", and ";
  if (too_many) m << "limits.max_particles is " << spec.max_particles;
  m << ". Raise dp (the count scales as dp^-" << dim << "), shrink the bodies (or their wall "
    << "layers)" << (too_many && !too_big ? ", or raise limits.max_particles" : "");
  throw CaseError(spec.file, 0, m.str());
}

std::string point_text(const Eigen::Vector3d& x, int dim) {
  std::ostringstream o;
  o << "(";
  for (int d = 0; d < dim; ++d) o << (d ? ", " : "") << x[d];
  o << ")";
  return o.str();
}

// A step that may fail on some ranks only (a distributed set-up): every rank learns whether
// one failed; the failing rank rethrows its own error, the others the lowest failing rank's
// message. One process: the step as it is.
template <class Fn>
void agreed(const SetupReduce& red, Fn&& fn) {
  if (red.size() == 1) {
    fn();
    return;
  }
  std::exception_ptr mine;
  std::string msg;
  try {
    fn();
  } catch (const std::exception& e) {
    mine = std::current_exception();
    msg = e.what();
    if (msg.empty()) msg = "set-up failed";
  }
  const std::string first = red.first_message(msg);
  if (mine) std::rethrow_exception(mine);
  if (!first.empty()) throw std::invalid_argument(first);
}

// This rank's share of the lattice in a distributed set-up: cuts along the longest axis of the
// bodies' bounds where the estimated counts (each body's spread evenly over its bounds along
// the axis) reach r / size of the total; a margin of one kernel support (the hydrostatic
// state of a wall particle reads the fluid within it).
geometry::FillShare fill_share(const std::vector<geometry::BodyGeometry>& geo,
                               const geometry::FillEstimate& est, int dim, double margin,
                               const SetupReduce& red) {
  std::vector<geometry::Aabb> boxes(geo.size());
  geometry::Aabb all;
  for (std::size_t b = 0; b < geo.size(); ++b) {
    const auto& g = geo[b];
    const geometry::BodyGeometry* shaped =
        g.shape ? &g
        : g.container >= 0 && static_cast<std::size_t>(g.container) < geo.size()
            ? &geo[static_cast<std::size_t>(g.container)]
            : nullptr;
    if (!shaped || !shaped->shape) continue;
    boxes[b] = shaped->shape->bounds();
    all.extend(boxes[b].min);
    all.extend(boxes[b].max);
  }
  geometry::FillShare share;
  share.margin = margin;
  int axis = 0;
  for (int d = 1; d < dim; ++d)
    if (all.max[d] - all.min[d] > all.max[axis] - all.min[axis]) axis = d;
  share.axis = axis;
  const double lo = all.min[axis], hi = all.max[axis];
  const int n = red.size(), me = red.rank();
  if (!(hi > lo) || n == 1) {
    if (me > 0) share.lo = share.hi = std::numeric_limits<double>::infinity();  // all on rank 0
    return share;
  }
  // Weighted by the fluid bodies (as the run's slabs are, run/run.cpp: fewer particles
  // move after the fill), by every body where no fluid body has an estimate.
  constexpr int kBins = 4096;
  std::vector<double> hist(kBins, 0.0);
  const double w = (hi - lo) / kBins;
  bool by_fluid = false;
  for (std::size_t b = 0; b < geo.size() && b < est.particles.size(); ++b)
    by_fluid = by_fluid || (geo[b].fluid && est.particles[b] > 0.0);
  for (std::size_t b = 0; b < geo.size() && b < est.particles.size(); ++b) {
    if (by_fluid && !geo[b].fluid) continue;
    if (!(boxes[b].max[axis] >= boxes[b].min[axis])) continue;
    const int b0 = std::clamp(static_cast<int>((boxes[b].min[axis] - lo) / w), 0, kBins - 1);
    const int b1 = std::clamp(static_cast<int>((boxes[b].max[axis] - lo) / w), 0, kBins - 1);
    for (int k = b0; k <= b1; ++k)
      hist[static_cast<std::size_t>(k)] += est.particles[b] / (b1 - b0 + 1);
  }
  double total = 0.0;
  for (const double c : hist) total += c;
  std::vector<double> cut(static_cast<std::size_t>(n) + 1);
  cut.front() = -std::numeric_limits<double>::infinity();
  cut.back() = std::numeric_limits<double>::infinity();
  double run = 0.0;
  int r = 1;
  for (int k = 0; k < kBins && r < n; ++k) {
    run += hist[static_cast<std::size_t>(k)];
    while (r < n && run * n >= total * r) cut[static_cast<std::size_t>(r++)] = lo + (k + 1) * w;
  }
  for (; r < n; ++r) cut[static_cast<std::size_t>(r)] = hi;
  share.lo = cut[static_cast<std::size_t>(me)];
  share.hi = cut[static_cast<std::size_t>(me) + 1];
  return share;
}

// The particle ids of a distributed fill: the index each point has in the whole case's fill
// (bodies in order, each in lattice order), from the per-row counts of every share. Margin
// points (a neighbour's) get kMarginId.
constexpr std::uint32_t kMarginId = 0xFFFFFFFFu;

std::vector<std::vector<std::uint64_t>> fill_ids(const std::vector<geometry::FilledBody>& filled,
                                                 const geometry::FillShare& share,
                                                 const SetupReduce& red,
                                                 std::vector<std::uint64_t>& body_total) {
  std::vector<std::vector<std::uint64_t>> ids(filled.size());
  std::uint64_t offset = 0;
  body_total.assign(filled.size(), 0);
  for (std::size_t b = 0; b < filled.size(); ++b) {
    const auto& fb = filled[b];
    std::vector<std::uint64_t> below(fb.row_owned.begin(), fb.row_owned.end());
    std::vector<std::uint64_t> all = below;
    red.exscan(below);
    red.sum(all);
    std::uint64_t row_base = offset;
    std::size_t at = 0;
    auto& out = ids[b];
    out.reserve(fb.points.size());
    for (std::size_t r = 0; r < fb.row_points.size(); ++r) {
      std::uint64_t next = row_base + below[r];
      for (std::uint32_t k = 0; k < fb.row_points[r]; ++k, ++at)
        out.push_back(share.owns(fb.points[at]) ? next++ : kMarginId);
      row_base += all[r];
    }
    body_total[b] = row_base - offset;
    offset = row_base;
  }
  return ids;
}

// The steps of setup_case, in order: each reads what the earlier ones left in the builder.
template <int D>
struct CaseBuilder {
  CaseBuilder(const CaseSpec& spec, const SetupReduce& red)
      : spec(spec),
        red(red),
        fill0(std::chrono::steady_clock::now()),
        distributed(red.size() > 1),
        node_share(distributed ? static_cast<double>(red.node_size()) / red.size() : 1.0),
        geo(case_geometry(spec, &s.meshes)) {
    fo.dim = D;
    fo.dp = spec.dp;
  }

  const CaseSpec& spec;
  const SetupReduce& red;
  CaseSetup<D> s;
  SolverParams& p = s.params;
  const std::chrono::steady_clock::time_point fill0;
  const bool distributed;
  const double node_share;
  geometry::FillOptions fo;
  const std::vector<geometry::BodyGeometry> geo;
  std::vector<geometry::FilledBody> filled;
  std::vector<std::vector<std::uint64_t>> ids;  // whole-case ids of a distributed fill
  std::vector<std::uint64_t> body_total;        // particles per body over every rank
  std::size_t total = 0;                        // this rank's particles (with its margin)
  bool any_mdbc = false;
  Vec<D> g, up;  // gravity and the unit vector against it
  double gnorm = 0.0;
  Vec<D> lo, hi;      // the particles' box, then grown by the moving bodies' paths
  Vec<D> dmin, dmax;  // the domain
  struct Swept {
    std::size_t body;
    Eigen::Vector3d lo, hi;
  };
  std::vector<Swept> rotating;  // the paths of bodies that turn (checked against periodic faces)

  // A margin particle (a neighbour's, read by the hydrostatic state near the share's faces).
  bool in_margin(std::size_t i) const { return distributed && s.particles.id[i] == kMarginId; }
  // Every rank's box.
  void reduce_box(Vec<D>& a, Vec<D>& z) const {
    if (!distributed) return;
    std::vector<double> v(2 * D);
    for (int d = 0; d < D; ++d) v[d] = -a[d], v[D + d] = z[d];
    red.max(v);
    for (int d = 0; d < D; ++d) a[d] = -v[d], z[d] = v[D + d];
  }

  // The lattice points of every body (this rank's share, with a margin, in a distributed set-up).
  void fill_lattice() {
    geometry::FillEstimate estimate;
    // (Agreed: each rank reads its own machine's free memory.)
    agreed(red, [&] {
      try {
        estimate = geometry::estimate_fill(geo, fo);
        check_size(spec, estimate, D, node_share);
      } catch (const std::invalid_argument& e) {
        throw CaseError(spec.file, 0, e.what());
      }
    });
    // A distributed set-up fills this rank's share, with a margin of one kernel support.
    const double support0 = kernel_support_factor(spec.kernel) * spec.coefh *
                            std::sqrt(static_cast<double>(D)) * spec.dp;
    if (distributed) fo.share = fill_share(geo, estimate, D, support0 * (1.0 + 1e-9), red);
    agreed(red, [&] {
      try {
        filled = geometry::fill_bodies(geo, fo);
      } catch (const std::invalid_argument& e) {
        throw CaseError(spec.file, 0, e.what());
      }
    });
    // Whole-case ids and counts (a distributed set-up; one process: the fill's order).
    if (distributed) {
      ids = fill_ids(filled, *fo.share, red, body_total);
      std::vector<std::uint64_t> in_region;
      for (const auto& fb : filled) in_region.push_back(fb.report.in_region);
      red.sum(in_region);
      for (std::size_t b = 0; b < filled.size(); ++b) {
        filled[b].report.particles = body_total[b];
        filled[b].report.in_region = in_region[b];
        if (body_total[b] == 0)
          throw CaseError(spec.file, 0,
                          "body '" + filled[b].report.name +
                              "' holds no particle at dp = " + std::to_string(spec.dp) +
                              " (is it thinner than dp, or inside a wall?)");
      }
      if (std::accumulate(body_total.begin(), body_total.end(), std::uint64_t{0}) >= kMarginId)
        throw CaseError(spec.file, 0,
                        "the case makes more than 2^32 - 1 particles (ids are 32-bit)");
    }
    s.fill_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - fill0).count();
  }

  // The solver's parameters from the case.
  void solver_params() {
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
    p.fixed_dt = spec.dt_fixed;
    p.rho_min_factor = spec.rho_min_factor;
    p.rho_max_factor = spec.rho_max_factor;
    p.boundary = spec.boundary;
    p.mdbc_slip = spec.mdbc_slip;
    p.mdbc_pressure = spec.mdbc_pressure;
    p.mdbc_det_min = spec.mdbc_det_min;
    p.shifting = spec.shifting;
    p.kernel_gradient_correction = spec.kernel_gradient_correction;
    p.kgc_det_min = spec.kgc_det_min;
    p.shepard_reinit = spec.shepard_reinit;
    p.shift_coefficient = spec.shift_coefficient;
    p.shift_surface_threshold = spec.shift_surface_threshold;
    p.shift_correct_density = spec.shift_correct_density;
    p.shift_mode = spec.shift_mode;
    p.dt_collapse_factor = spec.dt_collapse;
  }

  // Each body's motion law.
  void motion_laws() {
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
  }

  // The particles, body by body in fill order.
  void add_particles() {
    const double mass = spec.rho0 * std::pow(spec.dp, D);
    total = 0;
    for (const auto& fb : filled) total += fb.points.size();
    s.particles.reserve(total);
    for (std::size_t b = 0; b < filled.size(); ++b) {
      const auto& fb = filled[b];
      const bool fluid = fb.report.fluid;
      s.bodies.push_back({fb.report.name, fluid, distributed ? body_total[b] : fb.points.size()});
      s.fill.push_back(fb.report);
      for (std::size_t k = 0; k < fb.points.size(); ++k) {
        s.particles.add(fb.points[k].template head<D>(), Vec<D>::Zero(), spec.rho0, mass,
                        fluid ? Role::Fluid : Role::FixedWall, static_cast<std::uint16_t>(b));
        if (distributed) s.particles.id.back() = static_cast<std::uint32_t>(ids[b][k]);
      }
    }
    std::vector<std::vector<std::uint64_t>>().swap(ids);
  }

  // The wall model of each body and mDBC's wall normals; moving bodies placed.
  void wall_models() {
    // The wall model per body (bodies[].boundary, else physics.boundary.model). With any mDBC
    // body the run uses the mDBC module, which treats the DBC bodies' walls as DBC does.
    s.dbc_bodies.assign(spec.bodies.size(), 0);
    for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
      if (spec.bodies[b].kind == BodySpec::Kind::Fluid) continue;
      const bool mdbc = spec.bodies[b].boundary.value_or(spec.boundary) == BoundaryType::Mdbc;
      s.dbc_bodies[b] = !mdbc;
      any_mdbc = any_mdbc || mdbc;
    }
    s.params.boundary = any_mdbc ? BoundaryType::Mdbc : BoundaryType::Dbc;
    // mDBC: each wall particle's vector to its wall surface, from its body's geometry (zero on
    // fluid and on the DBC bodies' walls).
    if (any_mdbc)
      agreed(red, [&] {
        std::vector<Vec<D>> normals;
        normals.reserve(total);
        for (std::size_t b = 0; b < filled.size(); ++b) {
          const auto& fb = filled[b];
          if (fb.report.fluid || s.dbc_bodies[b]) {
            normals.resize(normals.size() + fb.points.size(), Vec<D>::Zero());
            continue;
          }
          std::vector<Eigen::Vector3d> n;
          try {
            n = geometry::wall_normals(geo[b], fb.points, fo, &geo);
          } catch (const std::invalid_argument& e) {
            throw CaseError(spec.file, spec.bodies[b].line, e.what());
          }
          for (const auto& v : n) normals.push_back(v.template head<D>());
        }
        s.particles.enable("normal", normals);
      });
    // The lattice points are in the particles now: free them before the set-up's later stages.
    std::vector<geometry::FilledBody>().swap(filled);

    // Moving bodies' particles become moving walls, placed at their pose at t = 0.
    // With mDBC's hydrostatic wall pressure they also carry their acceleration.
    MovingBodies<D>::prepare(s.particles, s.motions,
                             any_mdbc && p.mdbc_pressure == MdbcPressure::Hydrostatic);
  }

  // The floor, the still-water height and the sound speed.
  void still_water() {
    // Still-water height and c0 = coefsound sqrt(g H) (DualSPHysics' convention).
    g = p.gravity.template head<D>();
    gnorm = g.norm();
    up = gnorm > 0.0 ? Vec<D>(-g / gnorm) : Vec<D>::UnitY();
    double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      if (s.particles.role[i] != Role::Fluid) continue;
      const double z = s.particles.pos[i].dot(up);
      zmin = std::min(zmin, z);
      zmax = std::max(zmax, z);
    }
    if (distributed) {
      std::vector<double> z{-zmin, zmax};
      red.max(z);
      zmin = -z[0], zmax = z[1];
    }
    if (!std::isfinite(zmin))
      throw std::invalid_argument(spec.file + ": the case holds no fluid particle");
    s.floor = zmin - 0.5 * spec.dp;
    s.hswl = spec.hswl ? *spec.hswl : (zmax - zmin + spec.dp);
    p.c0 = spec.coefsound * std::sqrt(std::max(gnorm, 1e-12) * s.hswl);
  }

  // The particles' box over every rank.
  void particle_box() {
    // Domain: given, or the bounding box of all particles plus a margin (particles leaving it
    // are excluded). The margin leaves room for splashes above open tanks.
    lo = Vec<D>::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      lo = lo.cwiseMin(s.particles.pos[i]);
      hi = hi.cwiseMax(s.particles.pos[i]);
    }
    // Every rank's box; kept for the hydrostatic sort, which a receiving rank repeats.
    reduce_box(lo, hi);
    s.order_lo = lo;
    s.order_hi = hi;
  }

  // The box grown by the moving bodies' paths.
  void sweep_moving_bodies() {
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
      {
        Vec<D> a = blo.template head<D>(), z = bhi.template head<D>();
        reduce_box(a, z);
        blo.template head<D>() = a;
        bhi.template head<D>() = z;
      }
      if (D == 2) blo.z() = bhi.z() = 0.0;
      const auto corners = box_corners(blo, bhi);
      Eigen::Vector3d slo, shi;
      sweep_bounds(s.motions[b], spec.t_end, corners, slo, shi);
      // Along a periodic axis the path may cross the faces: the body comes back through the
      // other one (CellGrid wraps its particles and their reference positions).
      if (s.motions[b].rotates()) rotating.push_back({b, slo, shi});
      for (int d = 0; d < D; ++d)
        if (spec.periodic[static_cast<std::size_t>(d)]) slo[d] = blo[d], shi[d] = bhi[d];
      lo = lo.cwiseMin(Vec<D>(slo.template head<D>()));
      hi = hi.cwiseMax(Vec<D>(shi.template head<D>()));
    }
  }

  // The domain: the case's, or the default around the box.
  void domain() {
    // Default: the box plus 10 % of its size and 2h on every side, and above the water (against
    // gravity) a further 50 % of its height, so that splashes thrown out of an open tank fall
    // back into it instead of leaving the run through the top (DualSPHysics users raise the
    // top by 50 % for the same reason).
    const Vec<D> margin = (0.1 * (hi - lo)).array() + 2.0 * p.h;
    Vec<D> dlo = lo - margin, dhi = hi + margin;
    int up_axis = 0;
    for (int d = 0; d < D; ++d)
      if (std::abs(g[d]) > std::abs(g[up_axis])) up_axis = d;
    if (g[up_axis] <= 0.0)
      dhi[up_axis] += 0.5 * (hi - lo)[up_axis];
    else
      dlo[up_axis] -= 0.5 * (hi - lo)[up_axis];
    s.default_domain = !spec.domain_min;
    p.domain_min.setZero();
    p.domain_max.setZero();
    p.domain_min.template head<D>() =
        spec.domain_min ? Vec<D>(spec.domain_min->template head<D>()) : dlo;
    p.domain_max.template head<D>() =
        spec.domain_max ? Vec<D>(spec.domain_max->template head<D>()) : dhi;
  }

  // Turning bodies stay off the periodic faces.
  void check_periodic_paths() {
    // A body wrapped through a periodic face is moved by the period in its reference frame,
    // which is only its own image for a translation: a turning body must stay off the faces.
    for (const Swept& r : rotating)
      for (int d = 0; d < D; ++d) {
        if (!spec.periodic[static_cast<std::size_t>(d)]) continue;
        if (r.lo[d] >= p.domain_min[d] && r.hi[d] <= p.domain_max[d]) continue;
        const auto& body = spec.bodies[r.body];
        std::ostringstream m;
        m << "bodies[].motion: body '" << body.name << "' turns and its path up to time.end ("
          << r.lo[d] << " - " << r.hi[d] << " along "
          << "xyz"[d] << ") crosses the periodic faces at " << p.domain_min[d] << " and "
          << p.domain_max[d] << "; only translating bodies may cross a periodic face";
        throw CaseError(spec.file, body.line, m.str());
      }
  }

  // An explicit domain holds every particle and path.
  void check_explicit_domain() {
    // An explicit domain must hold every particle (and every moving body's path): what lies
    // outside would be excluded at the first step.
    dmin = p.domain_min.template head<D>();
    dmax = p.domain_max.template head<D>();
    if (!s.default_domain) {
      std::vector<std::uint64_t> outside(spec.bodies.size(), 0);
      std::vector<std::size_t> first(spec.bodies.size(), 0);
      for (std::size_t i = 0; i < s.particles.size(); ++i) {
        if (in_margin(i)) continue;
        const Vec<D>& x = s.particles.pos[i];
        if ((x.array() >= dmin.array()).all() && (x.array() <= dmax.array()).all()) continue;
        const std::size_t b = s.particles.body[i];
        if (outside[b]++ == 0) first[b] = i;
      }
      // The example: the body's first particle outside (lowest id) on any rank.
      std::vector<double> example(spec.bodies.size() * (D + 1), 0.0);
      if (distributed) {
        std::vector<std::uint64_t> any = outside;
        red.sum(any);
        if (std::any_of(any.begin(), any.end(), [](std::uint64_t c) { return c > 0; })) {
          std::vector<double> lowest(spec.bodies.size(), -std::numeric_limits<double>::infinity());
          for (std::size_t b = 0; b < spec.bodies.size(); ++b)
            if (outside[b]) lowest[b] = -static_cast<double>(s.particles.id[first[b]]);
          red.max(lowest);
          for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
            if (!outside[b] || -static_cast<double>(s.particles.id[first[b]]) != lowest[b])
              continue;
            example[b * (D + 1)] = 1.0;
            for (int d = 0; d < D; ++d) example[b * (D + 1) + 1 + d] = s.particles.pos[first[b]][d];
          }
          red.sum(example);
        }
        outside = any;
      } else {
        for (std::size_t b = 0; b < spec.bodies.size(); ++b)
          if (outside[b])
            for (int d = 0; d < D; ++d) example[b * (D + 1) + 1 + d] = s.particles.pos[first[b]][d];
      }
      for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
        if (outside[b] == 0) continue;
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (int d = 0; d < D; ++d) x[d] = example[b * (D + 1) + 1 + d];
        const bool fluid = spec.bodies[b].kind == BodySpec::Kind::Fluid;
        std::ostringstream m;
        m << "domain: " << outside[b] << " of the " << s.bodies[b].particles << " particles of "
          << (fluid ? "fluid" : "boundary") << " body '" << spec.bodies[b].name << "' (line "
          << spec.bodies[b].line << ") lie outside the domain " << point_text(p.domain_min, D)
          << " - " << point_text(p.domain_max, D) << ", e.g. at " << point_text(x, D)
          << (fluid ? "" : ": the domain cuts its walls") << "; enlarge domain (or leave it out "
          << "for the default)";
        throw CaseError(spec.file, spec.bodies[b].line, m.str());
      }
      Eigen::Vector3d plo = Eigen::Vector3d::Zero(), phi = Eigen::Vector3d::Zero();
      plo.template head<D>() = lo;
      phi.template head<D>() = hi;
      if ((lo.array() < dmin.array()).any() || (hi.array() > dmax.array()).any()) {
        throw CaseError(spec.file, 0,
                        "domain: the path of a moving body up to time.end spans " +
                            point_text(plo, D) + " - " + point_text(phi, D) +
                            ", beyond the domain " + point_text(p.domain_min, D) + " - " +
                            point_text(p.domain_max, D) + "; enlarge domain");
      }
    }
  }

  // The neighbour grid fits in memory; periodic extents hold two supports.
  void check_grid() {
    // The neighbour grid: cells of the kernel support over the domain, padded by one per side.
    // (Agreed: each rank reads its own machine's free memory.)
    agreed(red, [&] {
      const double support = kernel_support_factor(p.kernel) * p.h;
      for (int d = 0; d < D; ++d) {
        p.periodic[static_cast<std::size_t>(d)] = spec.periodic[static_cast<std::size_t>(d)];
        if (!spec.periodic[static_cast<std::size_t>(d)] || dmax[d] - dmin[d] >= 2.0 * support)
          continue;
        std::ostringstream m;
        m << "domain.periodic: the domain's extent along "
          << "xyz"[d] << " (" << dmax[d] - dmin[d]
          << " m) is the period and must be at least two kernel supports (" << 2.0 * support
          << " m)";
        throw CaseError(spec.file, 0, m.str());
      }
      double cells = 1.0;
      for (int d = 0; d < D; ++d) cells *= std::floor((dmax[d] - dmin[d]) / support) + 3.0;
      // The particles are built by now: what this process already holds counts as available to
      // the run (the estimate below includes them).
      const double free_now = available_memory_bytes();
      const double avail = free_now > 0.0 ? free_now + resident_bytes() : 0.0;  // 0: unknown
      // A distributed set-up: this machine's ranks hold their shares and a grid each.
      double particles = static_cast<double>(s.particles.size()), node_cells = cells;
      if (distributed) {
        particles = 0.0;
        for (const auto& b : s.bodies) particles += static_cast<double>(b.particles);
        particles *= node_share;
        node_cells *= red.node_size();
      }
      const double need = estimated_bytes(particles, node_cells, bytes_per_particle(spec, D));
      if (cells > 4.0e9 || (avail > 0.0 && need > 0.8 * avail)) {
        std::ostringstream m;
        m << std::setprecision(3) << "domain: " << point_text(p.domain_min, D) << " - "
          << point_text(p.domain_max, D) << " makes " << cells << " neighbour cells of " << support
          << " m (2h), needing about " << bytes_text(need) << " with the particles"
          << (avail > 0.0 ? "; this machine has " + bytes_text(avail) + " available" : "")
          << "; shrink the domain (at most 4e9 cells)";
        throw CaseError(spec.file, 0, m.str());
      }
    });
  }

  // Fill levels above a tank's top.
  void warn_fill_levels() {
    // Setup checks that need the particles: fill levels, fluid outside every tank, gauges.
    for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
      const BodySpec& body = spec.bodies[b];
      if (!body.fill_below || body.fill_container < 0) continue;
      const auto& tank = geo[static_cast<std::size_t>(body.fill_container)];
      const double top = tank.shape->bounds().max[D - 1];
      if (*body.fill_below > top) {
        std::ostringstream m;
        m << "warning: body '" << body.name << "' (line " << body.line << "): fill level "
          << *body.fill_below << " m lies above the top of '" << tank.name << "' (" << top
          << " m); the tank is filled to its top";
        s.warnings.push_back(m.str());
      }
    }
  }

  // Fluid outside every tank.
  void warn_loose_fluid() {
    {
      std::vector<const geometry::BodyGeometry*> tanks;
      for (const auto& gb : geo)
        if (!gb.fluid && gb.walls_inside && gb.shape) tanks.push_back(&gb);
      if (!tanks.empty()) {
        std::vector<std::uint64_t> loose(spec.bodies.size(), 0);
        for (std::size_t i = 0; i < s.particles.size(); ++i) {
          if (s.particles.role[i] != Role::Fluid || in_margin(i)) continue;
          Eigen::Vector3d x = Eigen::Vector3d::Zero();
          x.template head<D>() = s.particles.pos[i];
          bool in_one = false;
          for (const auto* t : tanks) {
            const geometry::Aabb box = t->shape->bounds();
            bool in = true;
            for (int d = 0; d < D; ++d) in = in && x[d] >= box.min[d] && x[d] <= box.max[d];
            in_one = in_one || in;
          }
          if (!in_one) ++loose[s.particles.body[i]];
        }
        red.sum(loose);
        for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
          if (loose[b] == 0) continue;
          s.warnings.push_back("warning: " + std::to_string(loose[b]) + " of the " +
                               std::to_string(s.bodies[b].particles) +
                               " particles of fluid body '" + spec.bodies[b].name + "' (line " +
                               std::to_string(spec.bodies[b].line) +
                               ") lie outside every tank (boundary body with walls: inside)");
        }
      }
    }
  }

  // Gauges inside the domain and not inside a solid.
  void check_gauges() {
    for (std::size_t k = 0; k < spec.gauges.size(); ++k) {
      const GaugeSpec& gs = spec.gauges[k];
      if (gs.kind == GaugeSpec::Kind::Force || gs.kind == GaugeSpec::Kind::Front) continue;
      Eigen::Vector3d at = gs.at;
      if (gs.normal && gs.kind == GaugeSpec::Kind::Pressure)
        at += gs.offset.value_or(p.h) * gs.normal->normalized();
      bool inside = true;
      for (int d = 0; d < D; ++d) inside = inside && at[d] >= dmin[d] && at[d] <= dmax[d];
      const std::string who = "gauges[" + std::to_string(k) + "] '" + gs.name + "'";
      if (!inside) {
        throw CaseError(spec.file, gs.line,
                        who + ": samples at " + point_text(at, D) + ", outside the domain " +
                            point_text(p.domain_min, D) + " - " + point_text(p.domain_max, D) +
                            ", where there is never fluid");
      }
      // A height line starts on a floor, a runup line lies on a slope.
      if (gs.kind == GaugeSpec::Kind::Height || gs.kind == GaugeSpec::Kind::Runup) continue;
      for (const auto& gb : geo) {
        // Structures only: beside a tank, "outside its shape" may be above an open face.
        if (gb.fluid || !gb.shape || gb.walls_inside) continue;
        if (!(gb.shape->signed_distance(at) < -0.5 * spec.dp)) continue;
        s.warnings.push_back("warning: " + who + " (line " + std::to_string(gs.line) +
                             ") samples at " + point_text(at, D) + ", inside the solid '" +
                             gb.name + "'; it will read nan");
        break;
      }
    }
  }

  // Damping zones and settling, with their warnings.
  void damping_and_settling() {
    // Damping zones and settling (checked by the reader): warnings for a zone that holds no
    // fluid at the start, and for a body that moves while the settling phase damps its waves.
    for (const DampingSpec& ds : spec.damping) s.damping.push_back(ds.zone);
    s.settling = spec.settling;
    std::vector<double> wet_zone;
    for (const DampingSpec& ds : spec.damping) {
      const DampingGeometry g = damping_geometry(ds.zone, D);
      bool wet = false;
      for (std::size_t i = 0; i < s.particles.size() && !wet; ++i)
        wet = s.particles.role[i] == Role::Fluid && damping_depth<D>(g, s.particles.pos[i]) >= 0.0;
      wet_zone.push_back(wet ? 1.0 : 0.0);
    }
    red.max(wet_zone);
    for (std::size_t z = 0; z < spec.damping.size(); ++z) {
      const DampingSpec& ds = spec.damping[z];
      if (wet_zone[z] == 0.0)
        s.warnings.push_back("warning: damping zone '" + ds.zone.name + "' (line " +
                             std::to_string(ds.line) +
                             ") holds no fluid at the start; check its position and direction");
    }
    if (s.settling) {
      for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
        const MotionSpec& m = spec.bodies[b].motion;
        if (m.type == MotionSpec::Type::None || m.start >= s.settling->duration) continue;
        std::ostringstream w;
        w << "warning: body '" << spec.bodies[b].name << "' (line " << spec.bodies[b].line
          << ") moves from t = " << m.start << " s, within time.settling (" << s.settling->duration
          << " s), which damps what it drives; set its motion start >= " << s.settling->duration;
        s.warnings.push_back(w.str());
      }
    }
  }

  // The hydrostatic initial densities (a distributed set-up drops its margin).
  void hydrostatic_start() {
    if (!distributed) {
      initialise_hydrostatic(s.particles, p);
    } else {
      // The whole case's levels and box, then this rank's share without its margin.
      HydrostaticFrame<D> frame;
      frame.lo = s.order_lo;  // the particles' box (lo, hi grew by moving bodies' paths)
      frame.hi = s.order_hi;
      if (gnorm > 0.0) {
        const auto mine = fluid_levels(s.particles, up, p.dp);
        std::vector<double> level(spec.bodies.size(), -std::numeric_limits<double>::infinity());
        for (const auto& [b, z] : mine) level[b] = z;
        red.max(level);
        for (std::size_t b = 0; b < level.size(); ++b)
          if (std::isfinite(level[b])) frame.level[static_cast<std::uint16_t>(b)] = level[b];
      }
      initialise_hydrostatic(s.particles, p, &frame);
      std::size_t kept = 0;
      std::vector<std::uint8_t> keep(s.particles.size());
      for (std::size_t i = 0; i < s.particles.size(); ++i) keep[i] = !in_margin(i);
      s.particles.for_each_field([&](const FieldInfo& f, auto& a) {
        if (!s.particles.enabled(f)) return;
        std::size_t w = 0;
        for (std::size_t i = 0; i < keep.size(); ++i)
          if (keep[i]) a[w++] = a[i];
        a.resize(w);
        kept = w;
      });
      s.particles.n_active = kept;
      s.distributed = true;
    }
  }

  // The hydrostatic start lies within the density bounds.
  void check_density_bounds() {
    // The hydrostatic start must lie inside the density bounds: a fluid particle outside them
    // would be deleted at the first step (with coefsound: 1, a fifth of the water at once).
    {
      const double lo_rho = p.rho_min_factor * p.rho0, hi_rho = p.rho_max_factor * p.rho0;
      std::size_t worst = s.particles.size(), count = 0;
      double worst_ratio = 1.0;
      for (std::size_t i = 0; i < s.particles.size(); ++i) {
        if (s.particles.role[i] != Role::Fluid) continue;
        const double rho = s.particles.rho[i];
        if (rho >= lo_rho && rho <= hi_rho) continue;
        ++count;
        const double r = std::max(rho / p.rho0, p.rho0 / rho);
        if (!(r <= worst_ratio)) worst_ratio = r, worst = i;
      }
      // The worst particle: [rho / rho0, id, body, position] from the rank that holds it.
      std::vector<double> named(3 + D, 0.0);
      if (count > 0) {
        named[0] = s.particles.rho[worst] / p.rho0;
        named[1] = s.particles.id[worst];
        named[2] = s.particles.body[worst];
        for (int d = 0; d < D; ++d) named[3 + d] = s.particles.pos[worst][d];
      }
      if (distributed) {
        std::vector<std::uint64_t> n{count};
        red.sum(n);
        if (n[0] > 0) {
          std::vector<double> top{count > 0 ? worst_ratio : 0.0};
          red.max(top);
          // The lowest rank with the worst ratio names its particle.
          std::vector<double> holder{count > 0 && worst_ratio == top[0] ? -red.rank() : -1e9};
          red.max(holder);
          if (-holder[0] != red.rank()) named.assign(named.size(), 0.0);
          red.sum(named);
        }
        count = n[0];
      }
      if (count > 0) {
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (int d = 0; d < D; ++d) x[d] = named[3 + d];
        std::ostringstream m;
        m << std::setprecision(4) << "the initial hydrostatic density of " << count
          << " fluid particles lies outside physics.density_bounds [" << p.rho_min_factor << ", "
          << p.rho_max_factor << "] rho0 (up to " << named[0] << " rho0, particle "
          << static_cast<std::uint64_t>(named[1]) << " of body '"
          << spec.bodies[static_cast<std::size_t>(named[2])].name << "' at " << point_text(x, D)
          << " m): with coefsound = " << spec.coefsound << ", c0 = " << p.c0
          << " m/s is too low for a water depth of " << s.hswl
          << " m. Raise physics.coefsound (DualSPHysics cases use 10-40) or widen "
             "physics.density_bounds";
        throw CaseError(spec.file, 0, m.str());
      }
    }
  }
};

}  // namespace

template <int D>
CaseSetup<D> setup_case(const CaseSpec& spec, const SetupReduce& red) {
  CaseBuilder<D> b(spec, red);
  b.fill_lattice();
  b.solver_params();
  b.motion_laws();
  b.add_particles();
  b.wall_models();
  b.still_water();
  b.particle_box();
  b.sweep_moving_bodies();
  b.domain();
  b.check_periodic_paths();
  b.check_explicit_domain();
  b.check_grid();
  b.warn_fill_levels();
  b.warn_loose_fluid();
  b.check_gauges();
  b.damping_and_settling();
  b.hydrostatic_start();
  b.check_density_bounds();
  return std::move(b.s);
}

template <int D>
Simulation<D> make_simulation(const CaseSetup<D>& setup, ParticleSet<D> particles,
                              std::unique_ptr<Exchange<D>> exchange) {
  typename Simulation<D>::Hooks hooks;
  if (MovingBodies<D>::any_moves(setup.motions))
    hooks.push_back(std::make_unique<MovingBodies<D>>(setup.motions));
  // The corrections first: the Shepard densities before the boundary model's ghost nodes read
  // them, the corrected gradient before any after_forces hook reads the accelerations.
  if (setup.params.shepard_reinit > 0)
    hooks.push_back(std::make_unique<ShepardReinit<D>>(setup.params.shepard_reinit));
  if (setup.params.kernel_gradient_correction)
    hooks.push_back(std::make_unique<KernelGradientCorrection<D>>(setup.params.kgc_det_min));
  if (setup.params.shifting == ShiftingModel::Fickian) {
    ShiftingParams sp;
    sp.coefficient = setup.params.shift_coefficient;
    sp.surface_threshold = setup.params.shift_surface_threshold;
    sp.correct_density = setup.params.shift_correct_density;
    sp.mode = setup.params.shift_mode;
    hooks.push_back(std::make_unique<ShiftingHook<D>>(sp));
  }
  // Damping after shifting. Shifting moves positions and damping changes velocities, so neither
  // undoes the other; in this order shifting's |v| dt is the velocity the step moved the
  // particles with, the zones damp at the positions the step ends at, and nothing in the step
  // changes a velocity after the damping.
  if (!setup.damping.empty()) hooks.push_back(std::make_unique<DampingZones<D>>(setup.damping));
  if (setup.settling) hooks.push_back(std::make_unique<Settling<D>>(*setup.settling));
  std::unique_ptr<BoundaryModel<D>> wall =
      setup.params.boundary == BoundaryType::Mdbc
          ? make_mdbc<D>(setup.params.mdbc_slip, setup.params.mdbc_det_min, setup.dbc_bodies,
                         setup.params.mdbc_pressure)
          : make_dbc<D>();
  return Simulation<D>(setup.params, std::move(particles), std::move(wall), std::move(hooks),
                       std::move(exchange));
}

template <int D>
double halo_width(const SolverParams& params, const ParticleSet<D>& particles) {
  double w = kernel_support_factor(params.kernel) * params.h;
  if (params.boundary == BoundaryType::Mdbc) {
    // A wall particle's ghost node lies at x + 2 n: its interpolation reaches one support
    // beyond that.
    double nmax = 0.0;
    for (const auto& n : particles.normal) nmax = std::max(nmax, n.norm());
    w += 2.0 * nmax;
  }
  return w;
}

template Simulation<2> make_simulation<2>(const CaseSetup<2>&, ParticleSet<2>,
                                          std::unique_ptr<Exchange<2>>);
template Simulation<3> make_simulation<3>(const CaseSetup<3>&, ParticleSet<3>,
                                          std::unique_ptr<Exchange<3>>);
template double halo_width<2>(const SolverParams&, const ParticleSet<2>&);
template double halo_width<3>(const SolverParams&, const ParticleSet<3>&);
template CaseSetup<2> setup_case<2>(const CaseSpec&, const SetupReduce&);
template CaseSetup<3> setup_case<3>(const CaseSpec&, const SetupReduce&);

}  // namespace swell
