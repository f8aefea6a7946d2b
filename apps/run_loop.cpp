// The time loop of `swell run`: steps the simulation and, between steps, writes snapshots
// (VTK, HDF5), gauges, diagnostics and checkpoints on their own schedules; restarts from a
// checkpoint; prints the progress line and the summary.
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "apps/case_runner.hpp"
#include "apps/gauge_set.hpp"
#include "apps/rank_setup.hpp"
#include "apps/run_log.hpp"
#include "apps/run_view.hpp"
#include "apps/stop_signals.hpp"
#include "bc/absorption.hpp"
#include "io/case_file.hpp"
#include "io/case_identity.hpp"
#include "io/gauge_csv.hpp"
#include "io/hdf5_file.hpp"
#include "io/model_names.hpp"
#include "io/provenance.hpp"
#include "io/run_folder.hpp"
#include "io/run_info.hpp"
#include "io/vtk_writer.hpp"
#include "parallel/comm.hpp"
#include "parallel/halo.hpp"
#include "solver/diagnostics.hpp"
#include "solver/physics/shifting.hpp"
#include "swell/version.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

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

// A repeating event at a fixed simulated-time interval. Fires at the first step reaching it;
// dt is never cut to hit it exactly (as DualSPHysics), so series times are step times.
struct Timer {
  double every = 0.0, next = 0.0;
  bool due(double t) const { return every > 0.0 && t >= next - 1e-12; }
  void advance(double t) {
    while (next <= t + 1e-12) next += every;
  }
};

// An output round of a decomposed run: what rank 0 tells every rank after a step (one number
// through comm.max; the others send 0), so that all of them make the same collective calls in
// the same order. Bits below 256; the number of the snapshot written in the round from 256 up.
enum RoundBits : unsigned {
  kRound = 1,        // something is due: the run's counts, then settle() at the end
  kGather = 2,       // snapshot/checkpoint without parallel HDF5: the whole state gathered
  kWatch = 4,        // the watchdog checks
  kDiag = 8,         // a diagnostics row
  kSnapshot = 16,    // a snapshot (VTK, HDF5)
  kCheckpoint = 32,  // a checkpoint (after a watchdog check)
  kGauges = 64,      // the gauges read the particles within their reach (gather_region)
};
struct Round {
  unsigned bits = 0;
  int snapshot = 0;  // its number, when kSnapshot
};
Round announce(const parallel::Comm& comm, Round r) {
  if (comm.size() == 1) return r;
  const auto v = static_cast<std::uint64_t>(comm.max(r.bits + 256.0 * r.snapshot));
  return {static_cast<unsigned>(v & 255u), static_cast<int>(v >> 8)};
}

// What the gauges know of the run besides the particles (every rank builds the same).
template <int D>
GaugeContext gauge_context(const CaseSetup<D>& setup) {
  GaugeContext c;
  c.params = setup.params;
  c.up_axis = D - 1;
  c.floor = setup.floor;
  c.line_top = setup.params.domain_max[D - 1];
  for (std::size_t b = 0; b < setup.bodies.size(); ++b)
    c.body_ids[setup.bodies[b].name] = static_cast<int>(b);
  return c;
}

// The diagnostics row (steps, dt, fluid count, mass, kinetic energy, max speed, front) over
// every rank: each its own particles, combined by `red` (collective).
template <int D, class Reduce>
std::vector<double> diagnostics_row(const ParticleSet<D>& local, const Reduce& red, long steps,
                                    double dt, const Vec<D>& up, double floor, double band,
                                    double dp) {
  const auto tot = fluid_totals(local);
  const double count = red.sum(static_cast<double>(tot.count));
  const double mass = red.sum(tot.mass), ke = red.sum(tot.kinetic_energy);
  const double vmax = red.max(tot.max_speed);
  const double front = red.max(surge_front(local, up, floor, band, dp));
  return {double(steps), dt, count, mass, ke, vmax, front};
}

// The VTK files of snapshot `k` (relative to the output folder): vtk/<name>[_part]_NNNN.vtp,
// or .pvtp on several ranks with shared output (pieces: vtk_piece_name).
std::string vtk_file(const std::string& name, const char* part, int k, bool pieces) {
  char num[32];
  std::snprintf(num, sizeof(num), "_%04d", k);
  return "vtk/" + name + part + num + (pieces ? ".pvtp" : ".vtp");
}

// The collective part of a snapshot of a decomposed run with shared output: every rank writes
// its VTK pieces and its rows of the HDF5 snapshot; rank 0 (h5/pvd given) also the .pvtp files,
// the .pvd entries and the HDF5 run file's index. `normals`: the pieces hold wall normals (mDBC).
// Every rank ends at the same agreement: on any rank's failure rank 0 throws, the others return
// false.
template <int D>
bool shared_snapshot(const fs::path& out, const CaseSpec& spec, int k, long step, double time,
                     const ParticleSet<D>& ps, const std::vector<double>& p,
                     const std::vector<std::string>& body_names, bool normals,
                     const WriteShare& share, const parallel::Comm& comm, Hdf5RunFile* h5,
                     std::vector<PvdSeries*> pvds) {
  const bool root = comm.rank() == 0;
  // Every rank's pieces, agreed; then rank 0's .pvtp files and .pvd entries, agreed: a .pvtp
  // is listed only once all its pieces exist.
  auto agreed = [&](const std::string& err, const std::string& what) {
    if (comm.min(err.empty() ? 1.0 : 0.0) == 1.0) return true;
    if (!root) {
      if (!err.empty()) std::fprintf(stderr, "swell (rank %d): %s\n", comm.rank(), err.c_str());
      return false;
    }
    throw std::runtime_error(err.empty() ? what : err);
  };
  if (spec.vtk) {
    std::vector<std::pair<const char*, ParticleFilter>> parts = {{"", ParticleFilter::All}};
    if (spec.vtk_split)
      parts.insert(parts.end(),
                   {{"_fluid", ParticleFilter::Fluid}, {"_boundary", ParticleFilter::Boundary}});
    auto piece_of = [&](std::size_t j) {
      const std::string rel = vtk_file(spec.name, parts[j].first, k, true);
      return rel.substr(0, rel.size() - 5) + ".vtp";  // vtk_piece_name adds the rank
    };
    std::string err;
    try {
      for (std::size_t j = 0; j < parts.size(); ++j)
        write_vtp<D>((out / vtk_piece_name(piece_of(j), comm.rank())).string(), ps, p,
                     parts[j].second, &body_names, time);
    } catch (const std::exception& e) {
      err = e.what();
    }
    if (!agreed(err, "another rank could not write its VTK piece of snapshot " + std::to_string(k) +
                         " (that rank's message is above)"))
      return false;
    try {
      for (std::size_t j = 0; j < parts.size() && root; ++j) {
        const std::string rel = vtk_file(spec.name, parts[j].first, k, true);
        std::vector<std::string> pieces;
        for (int r = 0; r < comm.size(); ++r)
          pieces.push_back(fs::path(vtk_piece_name(piece_of(j), r)).filename().string());
        write_pvtp((out / rel).string(), pieces, normals, true);
        pvds.at(j)->add(time, rel);
      }
    } catch (const std::exception& e) {
      err = e.what();
    }
    if (!agreed(err, "")) return false;
  }
  if (!spec.hdf5) return true;
  if (root) {
    h5->write_snapshot<D>(step, time, ps, p, &share);
    return true;
  }
  return write_snapshot_rows<D>((out / (spec.name + ".h5")).string(), step, ps, p, share);
}

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

template <int D>
RunMetadata make_metadata(const CaseSpec& spec, const CaseSetup<D>& setup, const RunSummary& sum,
                          const Provenance& prov) {
  RunMetadata m;
  m.provenance = prov;
  m.case_name = spec.name;
  m.case_file = spec.file;
  m.case_text = spec.text;
  m.version = SWELL_VERSION;
  m.dim = D;
  m.dp = spec.dp;
  m.h = setup.params.h;
  m.c0 = setup.params.c0;
  m.rho0 = setup.params.rho0;
  m.kernel = kernel_name(setup.params.kernel);
  m.n_fluid = sum.fluid;
  m.n_boundary = sum.boundary;
  for (const auto& b : setup.bodies) m.body_names.push_back(b.name);
  return m;
}

// The points where the ranks of a decomposed run agree that rank 0's own work (output folder,
// files, gauges, watchdog: things the other ranks do not do) went well. Rank 0 marks such work
// with root_work(); every rank then meets at agree(). If rank 0 throws in between, run_case
// posts its exit code through fail() at the agree() the others wait in, and they leave with it
// (PeerFailed). Failures every rank meets alike (the case set-up, an unstable step) need no
// agreement: each rank throws by itself. One rank: every call is a no-op.
class RunProtocol {
 public:
  explicit RunProtocol(parallel::Comm comm) : comm_(comm) {}
  void root_work() { pending_ = comm_.size() > 1 && comm_.rank() == 0; }
  void symmetric() { pending_ = false; }
  void agree() {
    if (comm_.size() == 1) return;
    pending_ = false;
    const int code = static_cast<int>(comm_.max(0.0));
    if (code != 0) throw PeerFailed(code);
  }
  void fail(int code) {
    if (!pending_) return;
    pending_ = false;
    comm_.max(static_cast<double>(code));
  }
  // A worker that failed where rank 0 may still be in its own work: meets it at the agreement.
  void post(int code) {
    if (comm_.size() > 1) comm_.max(static_cast<double>(code));
  }

 private:
  parallel::Comm comm_;
  bool pending_ = false;
};

// A restart continues the case its checkpoint was written by (the case identity: text, --set
// edits, input files, all but time.end). Every rank checks, so every rank refuses alike.
void check_checkpoint_case(const std::string& ck, const CaseTag& saved, const CaseTag& tag,
                           const std::string& case_file) {
  if (saved.identity.empty())
    throw std::invalid_argument(
        ck +
        " does not say which case wrote it (a checkpoint of an older Swell): restart "
        "needs a checkpoint written by this version; run the case afresh with --overwrite");
  if (saved.identity != tag.identity)
    throw std::invalid_argument(
        ck + " was written by case '" + saved.name + "' (" + saved.file + "), and " + case_file +
        " differs from it (case text, --set edits or an input file, other than time.end; case "
        "identity " +
        tag.identity.substr(0, 12) + " against " + saved.identity.substr(0, 12) +
        "): a restart continues the case the run was started with; run this one with "
        "--overwrite or -o another folder");
}

// A restart on as many ranks as wrote the checkpoint: this rank's place in it (every rank's
// counts from its decomposition record), so it reads only its own rows; none otherwise.
std::optional<WriteShare> restart_rows(const std::map<std::string, double>& saved,
                                       const parallel::Comm& comm) {
  const auto ranks = saved.find("decomposition.ranks");
  if (comm.size() == 1 || ranks == saved.end() || static_cast<int>(ranks->second) != comm.size())
    return std::nullopt;
  WriteShare w;
  w.rank = comm.rank();
  for (int r = 0; r < comm.size(); ++r) {
    const auto a = saved.find("decomposition.active." + std::to_string(r));
    const auto e = saved.find("decomposition.excluded." + std::to_string(r));
    if (a == saved.end() || e == saved.end()) return std::nullopt;  // read it whole instead
    w.active.push_back(static_cast<std::uint64_t>(a->second));
    w.excluded.push_back(static_cast<std::uint64_t>(e->second));
  }
  return w;
}

// How this rank reads a checkpoint at a restart: on as many ranks as wrote it, its own rows
// (restart_rows); on another number of ranks after a set-up in shares, a block of the active
// rows (rank 0 also every excluded row), whose particles then go to their slabs
// (build_simulation); otherwise (one rank, SWELL_WHOLE_SETUP=1) the whole file. No
// collective: every rank decides alike from the same file and set-up.
struct RestartRead {
  std::optional<WriteShare> rows;
  bool blocks = false;
  std::uint64_t first_row = 0;  // blocks: the file row of this rank's first active particle
};

RestartRead restart_read(const std::string& ck, const parallel::Comm& comm, bool distributed) {
  RestartRead r;
  r.rows = restart_rows(read_checkpoint_schedule(ck), comm);
  if (r.rows || comm.size() == 1 || !distributed) return r;
  const auto [active, total] = checkpoint_counts(ck);
  const auto n = static_cast<std::uint64_t>(comm.size());
  WriteShare w;
  w.rank = comm.rank();
  for (std::uint64_t k = 0; k < n; ++k) {
    const std::uint64_t a = active * k / n, b = active * (k + 1) / n;
    if (static_cast<int>(k) == comm.rank()) r.first_row = a;
    w.active.push_back(b - a);
    w.excluded.push_back(k == 0 ? total - active : 0);
  }
  r.rows = w;
  r.blocks = true;
  return r;
}

// This rank's simulation. One rank: the case's, as always. Several: this rank's slab of the
// particles (`all`: the set-up's or a checkpoint's) with a SlabExchange. A checkpoint written
// on the same number of ranks (`saved` has its decomposition) gives each rank back exactly the
// particles it held, in their order, and the slab bounds; otherwise the slabs are balanced by
// fluid particle count along the domain's longest axis.
// `read`: how a restart read the checkpoint (`all` is then this rank's rows or block).
template <int D>
Simulation<D> build_simulation(const CaseSetup<D>& setup, ParticleSet<D> all,
                               const std::map<std::string, double>* saved,
                               const parallel::Comm& comm, long rebalance_every,
                               const RestartRead* read = nullptr) {
  if (comm.size() == 1) return make_simulation<D>(setup, std::move(all));
  const bool mine_already = read && read->rows && !read->blocks;
  const bool blocks = read && read->blocks;
  // `all`: setup.particles may be moved. (The halo width is a reduction over the ranks where
  // each holds only its own particles.)
  const double width = mine_already || blocks || (setup.distributed && !saved)
                           ? comm.max(halo_width(setup.params, all))
                           : halo_width(setup.params, all);
  const SolverParams& pr = setup.params;
  const int n = comm.size();
  auto get = [&](const std::string& key) {
    const auto it = saved->find(key);
    if (it == saved->end())
      throw std::invalid_argument("checkpoint: no '" + key + "' in its decomposition record");
    return it->second;
  };
  parallel::Slabs slabs;
  ParticleSet<D> mine;
  if (saved && saved->count("decomposition.ranks") &&
      static_cast<int>(saved->at("decomposition.ranks")) == n) {
    slabs.axis = static_cast<int>(get("decomposition.axis"));
    parallel::GatherLayout layout;
    for (int r = 0; r <= n; ++r) {
      slabs.lo.push_back(get("decomposition.lo." + std::to_string(r)));
      if (r == n) break;
      layout.active.push_back(
          static_cast<std::uint64_t>(get("decomposition.active." + std::to_string(r))));
      layout.excluded.push_back(
          static_cast<std::uint64_t>(get("decomposition.excluded." + std::to_string(r))));
    }
    mine = mine_already ? std::move(all) : parallel::share_by_layout(all, layout, comm.rank());
  } else if (blocks) {
    // A block of the checkpoint's rows on each rank (another number of ranks than wrote it):
    // the slabs from the histogram over every rank, the particles to their slab's rank with
    // their file rows, which restore the file's order: the share a whole read would give.
    const int axis = parallel::longest_axis<D>(pr.domain_min.template head<D>(),
                                               pr.domain_max.template head<D>());
    slabs = parallel::balanced_slabs(all, axis, pr.domain_min[axis], pr.domain_max[axis], width,
                                     comm, 4096, 0, true);
    std::vector<std::uint64_t> row(all.size());
    std::iota(row.begin(), row.end(), read->first_row);
    parallel::redistribute(all, slabs, comm, &row);
    mine = std::move(all);
  } else if (setup.distributed && !saved) {
    // Each rank holds its share of a distributed set-up: the same slabs from the histogram
    // over every rank, then the particles travel to their slab's rank and each rank restores
    // the whole set's order (by id, then the set-up's stable cell sort): the share a whole-case
    // set-up would give it, in the same order.
    const double w = width;  // already the maximum over the ranks
    const int axis = parallel::longest_axis<D>(pr.domain_min.template head<D>(),
                                               pr.domain_max.template head<D>());
    slabs = parallel::balanced_slabs(all, axis, pr.domain_min[axis], pr.domain_max[axis], w, comm,
                                     4096, 0, true);
    parallel::redistribute(all, slabs, comm);
    std::vector<std::uint32_t> by_id(all.size());
    std::iota(by_id.begin(), by_id.end(), 0u);
    std::sort(by_id.begin(), by_id.end(),
              [&](std::uint32_t a, std::uint32_t b) { return all.id[a] < all.id[b]; });
    all.permute_in_place(by_id);
    std::vector<std::uint32_t>().swap(by_id);
    const double support = kernel_support_factor(pr.kernel) * pr.h;
    CellGrid<D> order(setup.order_lo.array() - support, setup.order_hi.array() + support, support);
    typename CellGrid<D>::Reorder in_place;
    in_place.in_place = true;
    order.sort(all, in_place);
    mine = std::move(all);
    return make_simulation<D>(
        setup, std::move(mine),
        std::make_unique<parallel::SlabExchange<D>>(comm, slabs, w, rebalance_every));
  } else {
    const int axis = parallel::longest_axis<D>(pr.domain_min.template head<D>(),
                                               pr.domain_max.template head<D>());
    slabs = parallel::balanced_slabs(all, axis, pr.domain_min[axis], pr.domain_max[axis], width,
                                     parallel::Comm::self(), 4096, n, true);
    mine = parallel::share_by_slabs(all, slabs, comm.rank());
  }
  all = ParticleSet<D>();  // the whole set is not kept on any rank
  return make_simulation<D>(
      setup, std::move(mine),
      std::make_unique<parallel::SlabExchange<D>>(comm, slabs, width, rebalance_every));
}

// The decomposition's figures for the run summary (collective; every rank calls it after the
// loop, rank 0 gets the text): halo images and bytes per step per rank, migration, the time
// in the exchange (communication and packing) against the loop, and the balance now.
template <int D>
std::string decomposition_report(const Simulation<D>& sim, const parallel::Comm& comm,
                                 double loop_seconds, long loop_steps) {
  const auto* ex = dynamic_cast<const parallel::SlabExchange<D>*>(sim.exchange());
  if (!ex || comm.size() == 1) return {};
  const parallel::HaloStats& h = ex->stats();
  const double n = comm.size(), steps = std::max(1L, loop_steps);
  const double images = comm.sum(static_cast<double>(h.images)) / n / steps;
  const double bytes = comm.sum(static_cast<double>(h.image_bytes)) / n / steps;
  const double migrated = comm.sum(static_cast<double>(h.migrated)) / n / steps;
  const double ex_max = comm.max(h.seconds), ex_mean = comm.sum(h.seconds) / n;
  const double loop_max = comm.max(loop_seconds);
  const auto counts = comm.gather_all(sim.fluid_count());
  std::uint64_t lo = counts.front(), hi = counts.front(), total = 0;
  for (auto c : counts) lo = std::min(lo, c), hi = std::max(hi, c), total += c;
  // Memory per rank: resident now and the peak (the set-up in shares, then the run).
  rusage use{};
  getrusage(RUSAGE_SELF, &use);
  const double now = resident_bytes() / 1048576.0, peak = use.ru_maxrss / 1024.0;
  const double now_lo = comm.min(now), now_hi = comm.max(now);
  const double peak_lo = comm.min(peak), peak_hi = comm.max(peak);
  std::ostringstream o;
  o << std::setprecision(3);
  o << "  decomposition:  " << comm.size() << " ranks, slabs along "
    << "xyz"[ex->slabs().axis] << " (halo width " << ex->width() << " m), rebalanced "
    << h.rebalances << " times\n"
    << "    per rank and step: " << images << " halo images (two builds), " << bytes / 1024.0
    << " KiB received, " << migrated << " particles migrated\n"
    << "    exchange time: " << ex_mean << " s mean, " << ex_max << " s max over ranks, "
    << 100.0 * ex_max / std::max(loop_max, 1e-9) << " % of the time loop\n"
    << "    fluid particles per rank now: " << lo << " - " << hi << " (imbalance "
    << static_cast<double>(hi) * n / std::max<double>(1.0, static_cast<double>(total)) << ")\n"
    << "    memory per rank: " << now_lo << " - " << now_hi << " MiB resident now, peak " << peak_lo
    << " - " << peak_hi << " MiB\n";
  return o.str();
}

// SWELL_GATHER_OUTPUT=1: every output of a decomposed run from the whole state gathered to
// rank 0, as before parallel output (the tests compare the two, bit for bit).
bool gather_everything() {
  const char* g = std::getenv("SWELL_GATHER_OUTPUT");
  return g && std::string(g) == "1";
}

// Whether the ranks write their own particles into snapshots and checkpoints (parallel HDF5),
// else rank 0 writes them from a gather.
// Collective: every rank gets the same answer (the environment may differ between nodes).
bool use_shared_output(const parallel::Comm& comm) {
  if (comm.size() == 1) return false;
  return comm.min(parallel_hdf5() && !gather_everything() ? 1.0 : 0.0) == 1.0;
}

// Ranks 1..N-1 of a decomposed run: the same simulation calls and collectives as rank 0's
// run_dim, in the same order, and no output of their own but their share of the snapshots and
// checkpoints (shared output).
template <int D>
RunSummary run_worker(const CaseSpec& spec, const RunOptions& opt, const parallel::Comm& comm) {
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const std::string out_dir = opt.out_dir.empty() ? "out/" + spec.name : opt.out_dir;
  const fs::path out(out_dir);
  RunProtocol proto(comm);
  std::optional<CaseSetup<D>> made;
  proto.agree();  // rank 0's checks of the folder, before the collective set-up
  try {
    made.emplace(rank_setup<D>(spec, comm));
  } catch (const std::exception&) {
    proto.post(2);  // meet rank 0 at the first agreement, then leave with this error
    throw;
  }
  CaseSetup<D>& setup = *made;
  proto.agree();  // rank 0: folder, logs, checkpoint checks
  std::optional<Simulation<D>> sim;
  if (opt.restart) {
    setup.particles = ParticleSet<D>();  // the checkpoint's particles replace the set-up's
    const std::string ck = latest_valid_checkpoint((out / "checkpoint.h5").string());
    const RestartRead read = restart_read(ck, comm, setup.distributed);
    Checkpoint<D> c = read_checkpoint<D>(ck, read.rows ? &*read.rows : nullptr);
    sim.emplace(build_simulation<D>(setup, std::move(c.particles), &c.schedule, comm,
                                    opt.rebalance_every, &read));
    SimulationClock clock = c.clock;
    clock.excluded = {};  // rank 0 carries the run's counts
    sim->restore(clock);
    sim->restore_hooks(c.schedule);
    check_checkpoint_case(ck, c.tag, CaseTag{case_identity(spec), spec.name, spec.file}, spec.file);
  } else {
    sim.emplace(
        build_simulation<D>(setup, std::move(setup.particles), nullptr, comm, opt.rebalance_every));
  }
  RunView<D> view(*sim, comm, use_shared_output(comm));
  view.reduce_counts();
  view.settle();
  Watchdog<D> watchdog(spec.watchdog, view.local(), setup.floor, view);
  std::vector<std::string> names;
  for (const auto& b : setup.bodies) names.push_back(b.name);
  watchdog.set_body_names(names);
  const Vec<D> up = Vec<D>::Unit(D - 1);
  const double band = 2.0 * setup.params.h;
  const std::string ck_path = (out / "checkpoint.h5").string();
  const GaugeRegion<D> region = gauge_region<D>(spec.gauges, gauge_context(setup));
  const bool normals = setup.params.boundary == BoundaryType::Mdbc;
  // The watchdog stops every rank alike; rank 0 says why (this rank leaves quietly).
  auto watch = [&] {
    try {
      watchdog.check(view.local(), view);
    } catch (const InstabilityError&) {
      throw PeerFailed(3);
    }
  };
  // Rank 0's output round, from this rank's side (see run_dim's `round`).
  auto round = [&](Round r) {
    if (!r.bits) return;
    view.reduce_counts();
    if (r.bits & kGather) view.gather();
    if (r.bits & kGauges) view.gather_region(region);
    if (r.bits & kWatch) watch();
    if (r.bits & kDiag)
      diagnostics_row(sim->particles(), view, sim->steps(), sim->dt(), up, setup.floor, band,
                      spec.dp);
    WriteShare share;
    const bool shared = view.shared_output() && (r.bits & (kSnapshot | kCheckpoint));
    if (shared) share = view.share();
    proto.agree();  // rank 0's own outputs
    if (shared && (r.bits & kSnapshot) &&
        !shared_snapshot<D>(out, spec, r.snapshot, sim->steps(), sim->time(), sim->particles(),
                            view.local_pressure(), names, normals, share, comm, nullptr, {}))
      throw PeerFailed(1);  // rank 0 says why
    if (r.bits & kCheckpoint) {
      watch();        // a checkpoint only of a healthy run
      proto.agree();  // rank 0 writes it (from a gather), or every rank its rows
      if (shared && !write_checkpoint_rows<D>(ck_path, sim->particles(), share))
        throw PeerFailed(1);
    }
    view.settle();
  };
  proto.agree();  // rank 0: watchdog, output files
  if (!opt.restart) round(announce(comm, {}));
  proto.agree();
  const auto loop0 = std::chrono::steady_clock::now();
  const long step0 = sim->steps();
  while (sim->time() < spec.t_end) {
    if (const int sig = static_cast<int>(comm.max(static_cast<double>(stop_requested())))) {
      round({kRound | kCheckpoint | (view.shared_output() ? 0u : unsigned{kGather}), 0});
      proto.agree();
      throw Interrupted(sig, "stopped");
    }
    sim->step();
    round(announce(comm, {}));
    proto.agree();  // rank 0: gauges, watchdog, outputs
  }
  const double loop_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop0).count();
  decomposition_report(*sim, comm, loop_s, sim->steps() - step0);
  return {};
}

template <int D>
RunSummary run_dim(const CaseSpec& spec, const RunOptions& opt, RunLog& log, RunProtocol& proto) {
  const parallel::Comm comm = parallel::Comm::world();
  if (comm.rank() != 0) return run_worker<D>(spec, opt, comm);
  proto.root_work();
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const std::string out_dir = opt.out_dir.empty() ? "out/" + spec.name : opt.out_dir;
  const fs::path out(out_dir);
  if (opt.restart && !fs::exists(out / "checkpoint.h5") && !fs::exists(out / "checkpoint.h5.prev"))
    throw std::invalid_argument("cannot restart: no checkpoint in " + out_dir +
                                " (expected checkpoint.h5 written by an earlier swell run)");
  // One run per folder at a time, for the whole run; a new run never mixes with an old one.
  const OutputLock lock(out_dir);
  if (!opt.restart && !opt.overwrite) {
    const auto old = run_files(out_dir);
    if (!old.empty()) {
      std::string list;
      for (std::size_t i = 0; i < old.size() && i < 4; ++i) list += (i ? ", " : "") + old[i];
      if (old.size() > 4) list += ", ... (" + std::to_string(old.size()) + " files)";
      throw std::invalid_argument("output folder " + out_dir + " already holds a run (" + list +
                                  "): use --overwrite to replace it, --restart " + out_dir +
                                  " to continue it, or -o to choose another folder");
    }
  }
  const CaseTag tag{case_identity(spec), spec.name, spec.file};
  Provenance prov = capture_provenance();
  prov.ranks = comm.size();

  const auto wall0 = std::chrono::steady_clock::now();
  // A failure here (rank 0's own checks above, or the set-up) is posted at the first
  // agreement, which the other ranks reach whether their set-up worked or not.
  if (comm.size() > 1) {
    proto.agree();  // the other ranks join the set-up now
    proto.root_work();
  }
  CaseSetup<D> setup = rank_setup<D>(spec, comm);
  RunSummary sum;
  for (const auto& b : setup.bodies) (b.fluid ? sum.fluid : sum.boundary) += b.particles;
  const std::size_t n_total = sum.fluid + sum.boundary;

  log << "case " << spec.name << " (" << spec.file << "): " << D << "D, dp = " << spec.dp
      << " m, h = " << setup.params.h << " m, c0 = " << setup.params.c0 << " m/s, "
      << omp_get_max_threads() << " thread(s)"
      << (comm.size() > 1 ? " on each of " + std::to_string(comm.size()) + " MPI ranks" : "")
      << "\n";
  for (const auto& b : setup.bodies)
    log << "  body " << b.name << " (" << (b.fluid ? "fluid" : "boundary") << "): " << b.particles
        << " particles\n";
  log << "  total: " << n_total << " particles (" << sum.fluid << " fluid, " << sum.boundary
      << " boundary)\n";
  {
    const auto& pr = setup.params;
    std::ostringstream d;
    for (int k = 0; k < D; ++k)
      d << (k ? " x " : "") << "[" << pr.domain_min[k] << ", " << pr.domain_max[k] << "]";
    log << "  domain: " << d.str() << " m"
        << (setup.default_domain ? " (default: the particles' box + 10 % + 2h, +50 % of its "
                                   "height above; set domain: to change)"
                                 : " (from the case file)")
        << "\n";
  }
  log << derived_quantities_text(spec, setup);
  {
    const auto& pr = setup.params;
    log << "  walls: " << boundary_name(pr.boundary);
    if (pr.boundary == BoundaryType::Mdbc) {
      log << " (slip " << mdbc_slip_name(pr.mdbc_slip) << ", pressure "
          << mdbc_pressure_name(pr.mdbc_pressure) << ", det_min " << pr.mdbc_det_min << ")";
      std::string dbc;  // bodies[].boundary: dbc inside an mDBC run
      for (std::size_t b = 0; b < setup.dbc_bodies.size(); ++b)
        if (setup.dbc_bodies[b]) dbc += (dbc.empty() ? "" : ", ") + setup.bodies[b].name;
      if (!dbc.empty()) log << ", DBC walls on " << dbc;
    }
    log << "; shifting: " << shifting_name(pr.shifting);
    if (pr.shifting == ShiftingModel::Fickian) {
      ShiftingParams sp;
      sp.surface_threshold = pr.shift_surface_threshold;
      log << " (dr = -A h |v| dt grad C, A = " << pr.shift_coefficient
          << ", free surface where div r < " << sp.threshold(D)
          << ", near walls: " << shift_mode_name(pr.shift_mode)
          << (pr.shift_correct_density ? ", density moved with the shift" : "") << ")";
    }
    log << "\n";
  }
  bool short_h_noted = false, artificial_noted = false;
  for (const auto& b : spec.bodies) {
    if (b.motion.type != MotionSpec::Type::Wave) continue;
    log << "  wavemaker " << b.name << ": " << b.motion.wave_label << "\n";
    // Measured on cases/wave_decay2d.yaml at H/dp 5 (README, Regular-wave flume): 44 % of the
    // height lost over three wavelengths at coefh 1, 12-15 % at coefh 1.2, 1.5 and 2.
    if (spec.coefh < 1.2 && !short_h_noted) {
      log << "  warning: wavemaker " << b.name << ": coefh " << spec.coefh
          << " < 1.2: a wave loses much of its height over a few wavelengths with this short "
             "smoothing length (measured: 44 % over three wavelengths at coefh 1 against 12 % "
             "at 1.5, H/dp 5); consider physics.coefh: 1.5\n";
      short_h_noted = true;
    }
    // The same case at coefh 1.5, H/dp 5: 11.9 % lost over three wavelengths with artificial
    // viscosity alpha 0.01 (nu = alpha h c0 / 2 (D + 2), Monaghan 1992), 4.2 % with alpha
    // 0.001, 3.5 % with water's laminar viscosity (README, Regular-wave flume).
    if (spec.viscosity_model == ViscosityModel::Artificial && spec.alpha > 0.001 &&
        !artificial_noted) {
      log << "  warning: wavemaker " << b.name << ": artificial viscosity alpha " << spec.alpha
          << " damps the wave like a viscosity alpha h c0 / " << 2 * (D + 2) << " = "
          << spec.alpha * setup.params.h * setup.params.c0 / (2 * (D + 2))
          << " m^2/s (measured at coefh 1.5, H/dp 5: 11.9 % of the height lost over three "
             "wavelengths with alpha 0.01 against 3.5 % with water's viscosity); consider "
             "physics.viscosity: {model: laminar, nu: 1.0e-6}\n";
      artificial_noted = true;
    }
    for (const auto& w : b.motion.wave_notes)
      log << "  warning: wavemaker " << b.name << ": " << w << "\n";
    if (b.motion.absorption) {
      const PaddleAbsorber a(b.motion);
      const auto& ab = *b.motion.absorption;
      log << "  absorption " << b.name << ": U_c = G (eta_T - eta_M), G = "
          << (ab.gain == MotionSpec::Absorption::Gain::Tuned ? "w_p / F(k_p d)" : "sqrt(g / d)")
          << " = " << a.gain() << " 1/s; eta_M on the line "
          << (ab.distance ? std::to_string(*ab.distance) + " m" : std::string("one support"))
          << " in front of the face, low-pass " << a.filter_time() << " s, drift " << a.drift_time()
          << " s\n";
    }
  }
  log << "  damping: " << damping_text(setup.damping, D) << "; settling: ";
  if (setup.settling)
    log << "t < " << setup.settling->duration
        << " s, v *= exp(-sigma dt), sigma = " << setup.settling->rate << " (1 + cos(pi t / "
        << setup.settling->duration << " s)) / 2 1/s";
  else
    log << "none";
  log << "\n";
  for (const auto& w : setup.warnings) log << "  " << w << "\n";

  // Gauge context, before the particles move into the simulation.
  const GaugeContext gctx = gauge_context(setup);
  const GaugeRegion<D> region = gauge_region<D>(spec.gauges, gctx);
  const RunMetadata meta = make_metadata(spec, setup, sum, prov);
  // The set-up worked: only now is an earlier run's output removed (--overwrite).
  if (!opt.restart && opt.overwrite) remove_run_files(out_dir);
  fs::create_directories(out / "vtk");
  log.attach(out / "run.log", opt.restart);  // the header so far, then every line
  // run_info.yaml: how this folder was made, written now (a run that dies still says it) and
  // again at the end; a restart adds its own entry after the earlier ones.
  RunInfo info;
  info.header = "how the files in this folder were produced (written by swell run)";
  info.kind = "sph";
  info.resolution = spec.dp;
  info.size = static_cast<long>(n_total);
  info.date = utc_minutes_now();
  if (opt.restart) {
    try {
      info.provenance = read_run_info(out_dir).provenance;
    } catch (const std::runtime_error& e) {
      // An unreadable record must not stop the restart: say so, keep this command's entry.
      log << "  warning: earlier provenance not kept: " << e.what() << "\n";
    }
  }
  info.provenance.push_back(prov);
  info.note = "running";
  write_run_info(out_dir, info);

  // Fresh start or continuation from the last valid checkpoint.
  std::map<std::string, double> schedule;
  std::optional<Simulation<D>> sim;
  double resume_after = -1.0;
  const std::string ck_path = (out / "checkpoint.h5").string();
  if (opt.restart) {
    const std::string ck = latest_valid_checkpoint(ck_path);
    if (checkpoint_dimension(ck) != D)
      throw std::invalid_argument(ck + " holds a " + std::to_string(checkpoint_dimension(ck)) +
                                  "D run, but " + spec.file + " is " + std::to_string(D) + "D");
    // The checkpoint's particles replace the set-up's; on as many ranks as wrote it, each rank
    // reads only its own rows.
    setup.particles = ParticleSet<D>();
    const RestartRead read = restart_read(ck, comm, setup.distributed);
    const auto& rows = read.rows;
    Checkpoint<D> c = read_checkpoint<D>(ck, rows ? &*rows : nullptr);
    std::uint64_t in_file = c.particles.total();
    if (rows) {
      in_file = 0;
      for (std::size_t r = 0; r < rows->active.size(); ++r)
        in_file += rows->active[r] + rows->excluded[r];
    }
    if (in_file != n_total)
      throw std::invalid_argument(ck + " holds " + std::to_string(in_file) + " particles but " +
                                  spec.file + " makes " + std::to_string(n_total) +
                                  ": restart needs the case the run was started with");
    proto.agree();  // the other ranks read the checkpoint now
    sim.emplace(build_simulation<D>(setup, std::move(c.particles), &c.schedule, comm,
                                    opt.rebalance_every, &read));
    sim->restore(c.clock);
    sim->restore_hooks(c.schedule);
    check_checkpoint_case(ck, c.tag, tag, spec.file);  // every rank, alike
    schedule = c.schedule;
    resume_after = c.clock.time;
    sum.restarted_from = c.clock.time;
    log << "  restart from " << ck << " at t = " << c.clock.time << " s, step " << c.clock.steps
        << "\n";
  } else {
    proto.agree();
    sim.emplace(
        build_simulation<D>(setup, std::move(setup.particles), nullptr, comm, opt.rebalance_every));
  }
  if (opt.restart) {
    // Exclusions by face (kept in the checkpoint's schedule; absent in older checkpoints).
    FaceExclusions f;
    for (int k = 0; k < FaceExclusions::kFaces; ++k) {
      const std::string key = std::string("excluded.") + FaceExclusions::name(k) + ".";
      const auto u = static_cast<std::size_t>(k);
      auto get = [&](const char* what, double fallback) {
        const auto it = schedule.find(key + what);
        return it == schedule.end() ? fallback : it->second;
      };
      f.particles[u] = static_cast<std::size_t>(get("particles", 0.0));
      f.fluid[u] = static_cast<std::size_t>(get("fluid", 0.0));
      f.fluid_mass[u] = get("fluid_mass", 0.0);
      f.first_time[u] = get("first_time", -1.0);
      f.last_time[u] = get("last_time", -1.0);
    }
    sim->restore_faces(f);
  }
  // What the outputs read: the simulation itself; on several ranks each rank's own particles,
  // combined, or gathered here.
  proto.symmetric();
  RunView<D> view(*sim, comm, use_shared_output(comm));
  view.reduce_counts();
  view.settle();
  Watchdog<D> watchdog(spec.watchdog, view.local(), setup.floor, view);
  proto.root_work();
  {
    std::vector<std::string> names;
    for (const auto& b : setup.bodies) names.push_back(b.name);
    watchdog.set_body_names(std::move(names));
  }
  double last_checkpoint = opt.restart ? resume_after : -1.0;

  const double t_end = spec.t_end;
  const double every = spec.output_every > 0.0 ? spec.output_every : t_end;
  Timer out_timer{every, 0.0}, diag_timer{every / 10.0, 0.0},
      ck_timer{spec.checkpoint_every > 0.0 ? spec.checkpoint_every : every, every};
  const double gauge_every = spec.gauge_every > 0.0 ? spec.gauge_every : every / 10.0;
  int snapshot = 0;
  if (opt.restart) {
    out_timer.next = schedule.at("next_output");
    diag_timer.next = schedule.at("next_diagnostics");
    ck_timer.next = schedule.at("next_checkpoint");
    snapshot = static_cast<int>(schedule.at("snapshot"));
    // VTK snapshots from after the checkpoint are written again (same numbers); none of a
    // later number may outlive the restart unlisted.
    remove_vtk_snapshots_from(out_dir, spec.name, snapshot);
  }

  // Outputs (continued after the checkpoint time on restart).
  PvdSeries pvd((out / (spec.name + ".pvd")).string());
  PvdSeries pvd_fluid((out / (spec.name + "_fluid.pvd")).string());
  PvdSeries pvd_bound((out / (spec.name + "_boundary.pvd")).string());
  if (opt.restart) {
    pvd.resume(resume_after);
    pvd_fluid.resume(resume_after);
    pvd_bound.resume(resume_after);
  }
  std::optional<Hdf5RunFile> h5;
  const std::string h5_path = (out / (spec.name + ".h5")).string();
  if (spec.hdf5) {
    if (opt.restart) {
      h5.emplace(Hdf5RunFile::open_for_append(h5_path, meta, resume_after));
    } else {
      h5.emplace(Hdf5RunFile::create(h5_path, meta));
    }
  }
  const Vec<D> up = Vec<D>::Unit(D - 1);
  const double band = 2.0 * setup.params.h;
  GaugeCsvFile diag(
      (out / "diagnostics.csv").string(),
      {"swell diagnostics, case " + spec.name, "front = largest x of fluid within " +
                                                   std::to_string(band) +
                                                   " m above the floor, plus dp/2"},
      // 2D: mass and energy per metre of depth.
      {"steps", "dt [s]", "fluid particles", D == 2 ? "fluid mass [kg/m]" : "fluid mass [kg]",
       D == 2 ? "kinetic energy [J/m]" : "kinetic energy [J]", "max speed [m/s]", "front x [m]"},
      resume_after);
  GaugeSet<D> gauges(spec.gauges, gauge_every, gctx, out_dir, spec.name, resume_after);
  gauges.load_schedule(schedule);

  // A snapshot from rank 0 alone: one rank, or the particles gathered here.
  auto write_snapshot = [&]() {
    const double t0 = omp_get_wtime();
    const auto& p = view.pressure();
    if (spec.vtk) {
      const std::string rel = vtk_file(spec.name, "", snapshot, false);
      write_vtp<D>((out / rel).string(), view.particles(), p, ParticleFilter::All, &meta.body_names,
                   sim->time());
      pvd.add(sim->time(), rel);
      if (spec.vtk_split) {
        const std::string rf = vtk_file(spec.name, "_fluid", snapshot, false),
                          rb = vtk_file(spec.name, "_boundary", snapshot, false);
        write_vtp<D>((out / rf).string(), view.particles(), p, ParticleFilter::Fluid,
                     &meta.body_names, sim->time());
        write_vtp<D>((out / rb).string(), view.particles(), p, ParticleFilter::Boundary,
                     &meta.body_names, sim->time());
        pvd_fluid.add(sim->time(), rf);
        pvd_bound.add(sim->time(), rb);
      }
    }
    if (h5) h5->write_snapshot<D>(sim->steps(), sim->time(), view.particles(), p);
    sum.output_seconds += omp_get_wtime() - t0;
  };
  // The checkpoint's schedule: the runner's timers, the gauges' and hooks' state, the faces'
  // exclusions and, on several ranks, the slabs and each rank's share of the file.
  auto checkpoint_schedule = [&](const std::optional<WriteShare>& share) {
    std::map<std::string, double> s;
    const FaceExclusions& fx = view.excluded_faces();
    for (int k = 0; k < FaceExclusions::kFaces; ++k) {
      const std::string key = std::string("excluded.") + FaceExclusions::name(k) + ".";
      const auto u = static_cast<std::size_t>(k);
      s[key + "particles"] = static_cast<double>(fx.particles[u]);
      s[key + "fluid"] = static_cast<double>(fx.fluid[u]);
      s[key + "fluid_mass"] = fx.fluid_mass[u];
      s[key + "first_time"] = fx.first_time[u];
      s[key + "last_time"] = fx.last_time[u];
    }
    s["next_output"] = out_timer.next;
    s["next_diagnostics"] = diag_timer.next;
    s["next_checkpoint"] = ck_timer.next;
    s["snapshot"] = snapshot;
    gauges.save_schedule(s);
    sim->save_hooks(s);
    if (view.decomposed()) {
      sim->exchange()->save(s);
      const auto& active = share ? share->active : view.layout().active;
      const auto& excluded = share ? share->excluded : view.layout().excluded;
      for (std::size_t r = 0; r < active.size(); ++r) {
        s["decomposition.active." + std::to_string(r)] = static_cast<double>(active[r]);
        s["decomposition.excluded." + std::to_string(r)] = static_cast<double>(excluded[r]);
      }
    }
    return s;
  };
  // What is due now (rank 0 decides; announce() tells the other ranks).
  auto plan = [&](bool after_step, bool final_state) {
    const double t = sim->time();
    Round r{0, snapshot};
    if (gauges.due(t) || (after_step && gauges.averages())) r.bits |= kGauges;
    if (after_step && watchdog.due(sim->steps())) r.bits |= kWatch;
    if (diag_timer.due(t)) r.bits |= kDiag;
    if (out_timer.due(t) || (final_state && out_timer.next > t + 1e-12 && snapshot > 0))
      r.bits |= kSnapshot;
    if (ck_timer.due(t) || final_state) r.bits |= kCheckpoint;
    if (!view.shared_output() && (r.bits & (kSnapshot | kCheckpoint))) r.bits |= kGather;
    if ((r.bits & kGauges) && gather_everything()) r.bits |= kGather;
    if (r.bits & kGather) r.bits &= ~unsigned{kGauges};  // the whole state serves the gauges
    if (r.bits) r.bits |= kRound;
    return r;
  };
  // Rank 0's side of an output round (run_worker has the others'): the collectives every rank
  // makes alike (the run's counts, the gathers, the watchdog, the diagnostics: a failure there
  // is every rank's); rank 0's own outputs (diagnostics row, gauges, from a gather the
  // snapshot), agreed; the shared snapshot; the watchdog again before a checkpoint (written only
  // while the run is healthy, after the step's other outputs as on one rank), rank 0's own
  // checkpoint from a gather, agreed, or every rank's rows; then settle().
  const bool normals = setup.params.boundary == BoundaryType::Mdbc;
  auto round = [&](Round r, bool after_step, bool stop) {
    if (!r.bits) return;
    const double t = sim->time();
    proto.symmetric();
    view.reduce_counts();
    if (r.bits & kGather) view.gather();
    if (r.bits & kGauges) view.gather_region(region);
    const bool warned = (r.bits & kWatch) && watchdog.check(view.local(), view);
    std::vector<double> row;
    if (r.bits & kDiag)
      row = diagnostics_row(sim->particles(), view, sim->steps(), sim->dt(), up, setup.floor, band,
                            spec.dp);
    std::optional<WriteShare> share;
    if (view.shared_output() && (r.bits & (kSnapshot | kCheckpoint))) share = view.share();
    proto.root_work();
    if (warned) log << "  " << watchdog.warning() << "\n" << std::flush;
    if (after_step && gauges.averages())
      gauges.accumulate(sim->dt(), view.particles(), view.pressure());
    if (r.bits & kDiag) {
      diag.write_row(t, row, std::vector<bool>(7, true));
      diag_timer.advance(t);
    }
    if (!stop && gauges.due(t))
      gauges.sample(t, view.particles(), view.pressure(), view.acceleration());
    if (r.bits & kSnapshot) {
      if (!share) write_snapshot();
      if (!stop) out_timer.advance(t);
      ++snapshot;
      ++sum.snapshots;
    }
    std::map<std::string, double> ck;
    if (r.bits & kCheckpoint) {
      if (!stop && ck_timer.due(t)) ck_timer.advance(t);
      ck = checkpoint_schedule(share);
      diag.flush();
      gauges.flush();
    }
    proto.agree();
    proto.symmetric();
    if (share && (r.bits & kSnapshot)) {
      const double t0 = omp_get_wtime();
      shared_snapshot<D>(out, spec, r.snapshot, sim->steps(), t, sim->particles(),
                         view.local_pressure(), meta.body_names, normals, *share, comm,
                         h5 ? &*h5 : nullptr, {&pvd, &pvd_fluid, &pvd_bound});
      sum.output_seconds += omp_get_wtime() - t0;
    }
    if (r.bits & kCheckpoint) {
      const double t0 = omp_get_wtime();
      const bool warned_now = watchdog.check(view.local(), view);
      proto.root_work();
      if (warned_now) log << "  " << watchdog.warning() << "\n" << std::flush;
      if (!share) write_checkpoint<D>(ck_path, view.particles(), view.clock(), ck, tag);
      proto.agree();
      proto.symmetric();
      if (share) write_checkpoint<D>(ck_path, sim->particles(), view.clock(), ck, tag, &*share);
      last_checkpoint = t;
      sum.output_seconds += omp_get_wtime() - t0;
    }
    view.settle();
    proto.root_work();
  };
  proto.agree();
  if (!opt.restart) round(announce(comm, plan(false, false)), false, false);
  proto.agree();

  const bool tty = isatty(fileno(stderr));
  const auto loop0 = std::chrono::steady_clock::now();
  auto last_progress = loop0;
  const long step0 = sim->steps();
  const double time0 = sim->time();
  try {
    while (sim->time() < t_end) {
      const int sig = view.decomposed()
                          ? static_cast<int>(comm.max(static_cast<double>(stop_requested())))
                          : stop_requested();
      if (sig) {
        // SIGINT/SIGTERM: everything consistent on disk at this step, then leave.
        if (opt.progress && tty) std::fprintf(stderr, "\n");
        round({kRound | kCheckpoint | (view.shared_output() ? 0u : unsigned{kGather}), 0}, false,
              true);
        proto.agree();
        std::ostringstream m;
        m << "stopped by "
          << (sig == SIGINT    ? "SIGINT"
              : sig == SIGTERM ? "SIGTERM"
                               : "a signal")
          << " at t = " << sim->time() << " s, step " << sim->steps() << "; checkpoint " << ck_path
          << " written\ncontinue with: swell run " << spec.file << " --restart " << out_dir;
        throw Interrupted(sig, m.str());
      }
      sim->step();
      round(announce(comm, plan(true, sim->time() >= t_end)), true, false);
      const auto now = std::chrono::steady_clock::now();
      if (now - last_progress > std::chrono::seconds(2) || sim->time() >= t_end) {
        last_progress = now;
        const double el = std::chrono::duration<double>(now - loop0).count();
        const double rate =
            static_cast<double>(sim->steps() - step0) * n_total / std::max(el, 1e-9);
        const double eta = el / (sim->time() - time0) * (t_end - sim->time());
        char line[256];
        std::snprintf(line, sizeof line,
                      "t = %.4f / %.4f s | step %ld | dt %.3e s | %.2f M particle-steps/s | ETA %s",
                      sim->time(), t_end, sim->steps(), sim->dt(), rate / 1e6,
                      format_duration(eta).c_str());
        log.file_line(line);
        if (opt.progress) {
          std::fprintf(stderr, "%s%s%s", tty ? "\r" : "", line, tty ? "   " : "\n");
          std::fflush(stderr);
        }
      }
      proto.agree();
    }
  } catch (const InstabilityError& e) {
    if (opt.progress && tty) std::fprintf(stderr, "\n");
    diag.flush();
    gauges.flush();
    std::ostringstream m;
    m << e.what() << ". ";
    if (last_checkpoint >= 0.0)
      m << "The last checkpoint, " << ck_path << " (t = " << last_checkpoint
        << " s), was taken while the run was healthy";
    else
      m << "No checkpoint was written (the run failed before the first one)";
    throw InstabilityError(m.str());
  }
  const auto wall1 = std::chrono::steady_clock::now();
  const double loop_s = std::chrono::duration<double>(wall1 - loop0).count();
  // Collective (the other ranks wait in it): before anything of rank 0's own that may throw.
  const std::string decomposition = decomposition_report(*sim, comm, loop_s, sim->steps() - step0);
  proto.symmetric();  // the other ranks are done
  if (opt.progress && tty) std::fprintf(stderr, "\n");
  diag.flush();
  gauges.flush();

  sum.wall_seconds = std::chrono::duration<double>(wall1 - wall0).count();
  sum.steps = sim->steps();
  sum.sim_time = sim->time();
  const long loop_steps = sim->steps() - step0;
  sum.particle_steps_per_second =
      static_cast<double>(n_total) * loop_steps / std::max(loop_s, 1e-9);
  sum.excluded = view.excluded();
  sum.faces = view.excluded_faces();
  sum.excluded_fluid_fraction = watchdog.excluded_fraction();
  sum.excluded_warning = watchdog.warned();
  sum.phases = sim->phase_times();

  std::ostringstream s;
  s << std::setprecision(4);
  s << "run summary: " << spec.name << "\n"
    << "  particles:      " << n_total << " (" << sum.fluid << " fluid, " << sum.boundary
    << " boundary)\n"
    << "  simulated time: " << sum.sim_time << " s in " << sum.steps << " steps"
    << (opt.restart ? " (restarted at t = " + std::to_string(resume_after) + " s)" : std::string())
    << "\n"
    << "  wall time:      " << sum.wall_seconds << " s (time loop " << loop_s << " s, "
    << omp_get_max_threads() << " thread(s))\n"
    << "  speed:          " << sum.particle_steps_per_second / 1e6 << " M particle-steps/s, "
    << loop_steps / std::max(loop_s, 1e-9) << " steps/s\n"
    << "  phases:         neighbours " << sum.phases.neighbour << " s, interaction "
    << sum.phases.interaction << " s, integration " << sum.phases.integration << " s, output "
    << sum.output_seconds << " s\n"
    << "  excluded:       " << sum.excluded.total() << " (out of domain "
    << sum.excluded.out_of_domain << ", non-finite " << sum.excluded.non_finite
    << ", density out of range " << sum.excluded.density_out_of_range << "); fluid mass "
    << std::round(watchdog.excluded_fraction() * 1e5) / 1e3 << " % of the initial";
  if (watchdog.warned())
    s << " (warning: over watchdog.warn_excluded = "
      << watchdog.limits().warn_excluded_fraction * 100 << " %)";
  s << "\n";
  {
    const FaceExclusions& fx = view.excluded_faces();
    for (int k = 0; k < FaceExclusions::kFaces; ++k) {
      const auto u = static_cast<std::size_t>(k);
      if (fx.particles[u] == 0) continue;
      s << "    through " << FaceExclusions::name(k) << ": " << fx.particles[u] << " ("
        << fx.fluid[u] << " fluid, " << fx.fluid_mass[u] << (D == 2 ? " kg/m" : " kg")
        << "), t = " << fx.first_time[u] << " - " << fx.last_time[u] << " s\n";
    }
  }
  s << decomposition;
  s << "  output:         " << out_dir << " (" << sum.snapshots << " snapshots, " << pvd.path()
    << ")\n";
  log << s.str();
  std::string made = "  made by:\n" + provenance_text(prov, "    ");
  if (opt.restart)
    made = "  made by (this restart; earlier commands: run_info.yaml):\n" +
           provenance_text(prov, "    ");
  write_file_atomically((out / "run_summary.txt").string(), s.str() + made);
  info.wall_seconds = sum.wall_seconds;
  info.end_time = sum.sim_time;
  {
    std::ostringstream note;
    note << sum.fluid << " fluid + " << sum.boundary << " boundary particles, " << sum.steps
         << " steps";
    if (opt.restart) note << " (restarted at t = " << resume_after << " s)";
    info.note = note.str();
  }
  write_run_info(out_dir, info);
  return sum;
}

}  // namespace

RunSummary run_case(const CaseSpec& spec, const RunOptions& options) {
  if (spec.dim != 2 && spec.dim != 3)
    throw std::invalid_argument(spec.file + ": dim must be 2 or 3");
  RunLog log(options.log ? *options.log : std::cout);
  // How the run ended goes into run.log too (if the run got that far; the caller prints it).
  auto ended = [&](const std::string& how) {
    if (log.attached()) log.file_line(how.c_str());
  };
  // Rank 0's failures in its own work reach the other ranks with its exit code.
  RunProtocol proto(parallel::Comm::world());
  try {
    return spec.dim == 2 ? run_dim<2>(spec, options, log, proto)
                         : run_dim<3>(spec, options, log, proto);
  } catch (const PeerFailed&) {
    throw;
  } catch (const Interrupted& e) {
    proto.fail(e.exit_code());
    ended(std::string("swell: ") + e.what());
    throw;
  } catch (const InstabilityError& e) {
    proto.fail(3);
    ended(std::string("error: the run went unstable: ") + e.what());
    throw;
  } catch (const CaseError& e) {
    proto.fail(2);
    ended(std::string("error: ") + e.what());
    throw;
  } catch (const std::invalid_argument& e) {
    proto.fail(2);
    ended(std::string("error: ") + e.what());
    throw;
  } catch (const std::exception& e) {
    proto.fail(1);
    ended(std::string("error: ") + e.what());
    throw;
  }
}

}  // namespace swell
