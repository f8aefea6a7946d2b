// The run library's story: a set-up case stepped to its end with its outputs. Run<D> is one
// run on one rank: every rank of a decomposed run makes the same object and walks the same
// methods in the same order, so their collective calls match by construction; rank 0 alone
// (root_) owns the output folder, the log, the series files and the gauges, and its own work is
// marked by the RunProtocol so that its failures reach the other ranks.
//
//   open()    the folder (rank 0), the case set up (every rank, in shares), the header
//   start()   the simulation, fresh or from the last valid checkpoint
//   watch()   what the outputs read (RunView), the watchdog, the output schedules and files
//   loop()    for each step: step(), then an output round (gauges, diagnostics, snapshot,
//             checkpoint) as plan() decides and announce() tells every rank
//   finish()  the summary, run_summary.txt and run_info.yaml
#include "run/run.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "case/identity.hpp"
#include "case/reader.hpp"
#include "io/gauge_csv.hpp"
#include "io/hdf5_file.hpp"
#include "io/provenance.hpp"
#include "io/run_folder.hpp"
#include "io/run_info.hpp"
#include "io/vtk_writer.hpp"
#include "parallel/comm.hpp"
#include "run/gauge_set.hpp"
#include "run/outputs.hpp"
#include "run/protocol.hpp"
#include "run/rank_setup.hpp"
#include "run/ranks.hpp"
#include "run/restart.hpp"
#include "run/run_header.hpp"
#include "run/run_log.hpp"
#include "run/run_view.hpp"
#include "run/stop_signals.hpp"
#include "solver/diagnostics.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

template <int D>
class Run {
 public:
  Run(const CaseSpec& spec, const RunOptions& opt, RunLog& log, RunProtocol& proto)
      : spec_(spec),
        opt_(opt),
        log_(log),
        proto_(proto),
        comm_(parallel::Comm::world()),
        root_(comm_.rank() == 0),
        out_dir_(opt.out_dir.empty() ? "out/" + spec.name : opt.out_dir),
        out_(out_dir_),
        ck_path_((out_ / "checkpoint.h5").string()) {}

  // The whole run; rank 0 returns the summary, the other ranks an empty one.
  RunSummary execute() {
    open();
    start();
    watch();
    loop();
    return finish();
  }

 private:
  void open();
  void check_folder();
  void prepare_folder();
  void start();
  void read_restart(std::optional<Checkpoint<D>>& c, RestartRead& read);
  void watch();
  void open_series();
  void loop();
  RunSummary finish();

  Round plan(bool after_step, bool final_state);
  void round(Round r, bool after_step, bool stop);
  bool check_watchdog();
  void write_snapshot();
  std::map<std::string, double> checkpoint_schedule(const std::optional<WriteShare>& share);
  [[noreturn]] void stop_now(int sig);
  void progress();

  const CaseSpec& spec_;
  const RunOptions& opt_;
  RunLog& log_;
  RunProtocol& proto_;
  const parallel::Comm comm_;
  const bool root_;  // rank 0: the folder, the log, the series files, the gauges
  const std::string out_dir_;
  const fs::path out_;
  const std::string ck_path_;
  std::optional<OutputLock> lock_;  // first in, last out: held until everything is written
  CaseTag tag_;
  Provenance prov_;
  std::chrono::steady_clock::time_point wall0_, loop0_, last_progress_;
  long step0_ = 0;
  double time0_ = 0.0;

  // Every rank.
  std::optional<CaseSetup<D>> setup_;
  std::optional<GaugeRegion<D>> region_;
  std::optional<Simulation<D>> sim_;
  std::optional<RunView<D>> view_;
  std::optional<Watchdog<D>> watchdog_;
  std::vector<std::string> body_names_;
  Vec<D> up_ = Vec<D>::Unit(D - 1);
  double band_ = 0.0;
  bool normals_ = false;
  std::string restart_from_;                // a restart's checkpoint file
  std::map<std::string, double> schedule_;  // a restart's checkpoint schedule
  double resume_after_ = -1.0;              // a restart's checkpoint time
  double last_checkpoint_ = -1.0;

  // Rank 0.
  RunSummary sum_;
  std::size_t n_total_ = 0;
  GaugeContext gctx_;
  RunMetadata meta_;
  RunInfo info_;
  Timer out_timer_, diag_timer_, ck_timer_;
  int snapshot_ = 0;
  bool tty_ = false;
  std::optional<PvdSeries> pvd_, pvd_fluid_, pvd_bound_;
  std::optional<Hdf5RunFile> h5_;
  std::optional<GaugeCsvFile> diag_;
  std::optional<GaugeSet<D>> gauges_;
};

// Rank 0 checks the folder; every rank sets up its share of the case; rank 0 prints the header
// and makes the folder ready (an earlier run removed only now, with --overwrite).
template <int D>
void Run<D>::open() {
  proto_.root_work();
  if (opt_.threads > 0) omp_set_num_threads(opt_.threads);
  if (root_) {
    check_folder();
    tag_ = CaseTag{case_identity(spec_), spec_.name, spec_.file};
    prov_ = capture_provenance();
    prov_.ranks = comm_.size();
  }
  wall0_ = std::chrono::steady_clock::now();
  // A failure of rank 0's checks is posted at this agreement, which the other ranks reach
  // before the collective set-up.
  proto_.agree();
  proto_.root_work();
  try {
    setup_.emplace(rank_setup<D>(spec_, comm_));
    region_.emplace(gauge_region<D>(spec_.gauges, gauge_context(*setup_)));
  } catch (const std::exception&) {
    if (!root_) proto_.post(2);  // meet rank 0 at its next agreement, then leave with this error
    throw;
  }
  if (!root_) return;
  for (const auto& b : setup_->bodies) (b.fluid ? sum_.fluid : sum_.boundary) += b.particles;
  n_total_ = sum_.fluid + sum_.boundary;
  log_ << run_header<D>(spec_, *setup_, comm_.size());
  // Gauge context, before the particles move into the simulation.
  gctx_ = gauge_context(*setup_);
  meta_ = make_metadata(spec_, *setup_, sum_, prov_);
  prepare_folder();
}

// A restart needs a checkpoint; one run per folder at a time, for the whole run; a new run
// never mixes with an old one.
template <int D>
void Run<D>::check_folder() {
  if (opt_.restart && !fs::exists(out_ / "checkpoint.h5") &&
      !fs::exists(out_ / "checkpoint.h5.prev"))
    throw std::invalid_argument("cannot restart: no checkpoint in " + out_dir_ +
                                " (expected checkpoint.h5 written by an earlier swell run)");
  lock_.emplace(out_dir_);
  if (!opt_.restart && !opt_.overwrite) {
    const auto old = run_files(out_dir_);
    if (!old.empty()) {
      std::string list;
      for (std::size_t i = 0; i < old.size() && i < 4; ++i) list += (i ? ", " : "") + old[i];
      if (old.size() > 4) list += ", ... (" + std::to_string(old.size()) + " files)";
      throw std::invalid_argument("output folder " + out_dir_ + " already holds a run (" + list +
                                  "): use --overwrite to replace it, --restart " + out_dir_ +
                                  " to continue it, or -o to choose another folder");
    }
  }
}

// The set-up worked: an earlier run's files go (--overwrite), the log file opens with the
// header so far, and run_info.yaml says how this folder is being made (written now, so a run
// that dies still says it, and again at the end; a restart adds its entry to the earlier ones).
template <int D>
void Run<D>::prepare_folder() {
  if (!opt_.restart && opt_.overwrite) remove_run_files(out_dir_);
  fs::create_directories(out_ / "vtk");
  log_.attach(out_ / "run.log", opt_.restart);
  info_.header = "how the files in this folder were produced (written by swell run)";
  info_.kind = "sph";
  info_.resolution = spec_.dp;
  info_.size = static_cast<long>(n_total_);
  info_.date = utc_minutes_now();
  if (opt_.restart) {
    try {
      info_.provenance = read_run_info(out_dir_).provenance;
    } catch (const std::runtime_error& e) {
      // An unreadable record must not stop the restart: say so, keep this command's entry.
      log_ << "  warning: earlier provenance not kept: " << e.what() << "\n";
    }
  }
  info_.provenance.push_back(prov_);
  info_.note = "running";
  write_run_info(out_dir_, info_);
}

// This rank's simulation: from the set-up, or from the last valid checkpoint (rank 0 reads and
// checks it first, then the others read their rows).
template <int D>
void Run<D>::start() {
  CaseSetup<D>& setup = *setup_;
  if (!opt_.restart) {
    proto_.agree();
    sim_.emplace(build_simulation<D>(setup, std::move(setup.particles), nullptr, comm_,
                                     opt_.rebalance_every));
    return;
  }
  std::optional<Checkpoint<D>> c;
  RestartRead read;
  if (root_) read_restart(c, read);
  proto_.agree();  // the other ranks read the checkpoint now
  if (!root_) read_restart(c, read);
  sim_.emplace(build_simulation<D>(setup, std::move(c->particles), &c->schedule, comm_,
                                   opt_.rebalance_every, &read));
  SimulationClock clock = c->clock;
  if (!root_) clock.excluded = {};  // rank 0 carries the run's counts
  sim_->restore(clock);
  sim_->restore_hooks(c->schedule);
  if (!root_) tag_ = CaseTag{case_identity(spec_), spec_.name, spec_.file};
  const std::string& ck = restart_from_;
  check_checkpoint_case(ck, c->tag, tag_, spec_.file);  // every rank, alike
  if (!root_) return;
  schedule_ = c->schedule;
  resume_after_ = c->clock.time;
  sum_.restarted_from = c->clock.time;
  log_ << "  restart from " << ck << " at t = " << c->clock.time << " s, step " << c->clock.steps
       << "\n";
  // Exclusions by face (kept in the checkpoint's schedule; absent in older checkpoints).
  FaceExclusions f;
  for (int k = 0; k < FaceExclusions::kFaces; ++k) {
    const std::string key = std::string("excluded.") + FaceExclusions::name(k) + ".";
    const auto u = static_cast<std::size_t>(k);
    auto get = [&](const char* what, double fallback) {
      const auto it = schedule_.find(key + what);
      return it == schedule_.end() ? fallback : it->second;
    };
    f.particles[u] = static_cast<std::size_t>(get("particles", 0.0));
    f.fluid[u] = static_cast<std::size_t>(get("fluid", 0.0));
    f.fluid_mass[u] = get("fluid_mass", 0.0);
    f.first_time[u] = get("first_time", -1.0);
    f.last_time[u] = get("last_time", -1.0);
  }
  sim_->restore_faces(f);
}

// The checkpoint's particles replace the set-up's; on as many ranks as wrote it, each rank
// reads only its own rows. Rank 0 checks that it is this case's dimension and size.
template <int D>
void Run<D>::read_restart(std::optional<Checkpoint<D>>& c, RestartRead& read) {
  restart_from_ = latest_valid_checkpoint(ck_path_);
  const std::string& ck = restart_from_;
  if (root_ && checkpoint_dimension(ck) != D)
    throw std::invalid_argument(ck + " holds a " + std::to_string(checkpoint_dimension(ck)) +
                                "D run, but " + spec_.file + " is " + std::to_string(D) + "D");
  setup_->particles = ParticleSet<D>();
  read = restart_read(ck, comm_, setup_->distributed);
  const auto& rows = read.rows;
  c.emplace(read_checkpoint<D>(ck, rows ? &*rows : nullptr));
  if (!root_) return;
  std::uint64_t in_file = c->particles.total();
  if (rows) {
    in_file = 0;
    for (std::size_t r = 0; r < rows->active.size(); ++r)
      in_file += rows->active[r] + rows->excluded[r];
  }
  if (in_file != n_total_)
    throw std::invalid_argument(ck + " holds " + std::to_string(in_file) + " particles but " +
                                spec_.file + " makes " + std::to_string(n_total_) +
                                ": restart needs the case the run was started with");
}

// What the outputs read (the simulation itself; on several ranks each rank's own particles,
// combined, or gathered to rank 0), the watchdog, rank 0's series files; then the first
// output round of a fresh run (the initial state).
template <int D>
void Run<D>::watch() {
  proto_.symmetric();
  view_.emplace(*sim_, comm_, use_shared_output(comm_));
  view_->reduce_counts();
  view_->settle();
  watchdog_.emplace(spec_.watchdog, view_->local(), setup_->floor, *view_);
  proto_.root_work();
  for (const auto& b : setup_->bodies) body_names_.push_back(b.name);
  watchdog_->set_body_names(body_names_);
  band_ = 2.0 * setup_->params.h;
  normals_ = setup_->params.boundary == BoundaryType::Mdbc;
  last_checkpoint_ = opt_.restart ? resume_after_ : -1.0;
  if (root_) open_series();
  proto_.agree();  // rank 0: watchdog, output files
  if (!opt_.restart) round(announce(comm_, root_ ? plan(false, false) : Round{}), false, false);
  proto_.agree();
}

// Rank 0's output schedules and series files (continued after the checkpoint on a restart).
template <int D>
void Run<D>::open_series() {
  const double t_end = spec_.t_end;
  const double every = spec_.output_every > 0.0 ? spec_.output_every : t_end;
  out_timer_ = Timer{every, 0.0};
  diag_timer_ = Timer{every / 10.0, 0.0};
  ck_timer_ = Timer{spec_.checkpoint_every > 0.0 ? spec_.checkpoint_every : every, every};
  const double gauge_every = spec_.gauge_every > 0.0 ? spec_.gauge_every : every / 10.0;
  if (opt_.restart) {
    out_timer_.next = schedule_.at("next_output");
    diag_timer_.next = schedule_.at("next_diagnostics");
    ck_timer_.next = schedule_.at("next_checkpoint");
    snapshot_ = static_cast<int>(schedule_.at("snapshot"));
    // VTK snapshots from after the checkpoint are written again (same numbers); none of a
    // later number may outlive the restart unlisted.
    remove_vtk_snapshots_from(out_dir_, spec_.name, snapshot_);
  }
  pvd_.emplace((out_ / (spec_.name + ".pvd")).string());
  pvd_fluid_.emplace((out_ / (spec_.name + "_fluid.pvd")).string());
  pvd_bound_.emplace((out_ / (spec_.name + "_boundary.pvd")).string());
  if (opt_.restart) {
    pvd_->resume(resume_after_);
    pvd_fluid_->resume(resume_after_);
    pvd_bound_->resume(resume_after_);
  }
  const std::string h5_path = (out_ / (spec_.name + ".h5")).string();
  if (spec_.hdf5) {
    if (opt_.restart)
      h5_.emplace(Hdf5RunFile::open_for_append(h5_path, meta_, resume_after_));
    else
      h5_.emplace(Hdf5RunFile::create(h5_path, meta_));
  }
  diag_.emplace(
      (out_ / "diagnostics.csv").string(),
      std::vector<std::string>{"swell diagnostics, case " + spec_.name,
                               "front = largest x of fluid within " + std::to_string(band_) +
                                   " m above the floor, plus dp/2"},
      // 2D: mass and energy per metre of depth.
      std::vector<std::string>{
          "steps", "dt [s]", "fluid particles", D == 2 ? "fluid mass [kg/m]" : "fluid mass [kg]",
          D == 2 ? "kinetic energy [J/m]" : "kinetic energy [J]", "max speed [m/s]", "front x [m]"},
      resume_after_);
  gauges_.emplace(spec_.gauges, gauge_every, gctx_, out_dir_, spec_.name, resume_after_);
  gauges_->load_schedule(schedule_);
}

// Steps to time.end, an output round after each step; a stop signal ends the run cleanly
// between two steps.
template <int D>
void Run<D>::loop() {
  tty_ = isatty(fileno(stderr));
  loop0_ = std::chrono::steady_clock::now();
  last_progress_ = loop0_;
  step0_ = sim_->steps();
  time0_ = sim_->time();
  try {
    while (sim_->time() < spec_.t_end) {
      const int sig = view_->decomposed()
                          ? static_cast<int>(comm_.max(static_cast<double>(stop_requested())))
                          : stop_requested();
      if (sig) stop_now(sig);
      sim_->step();
      round(announce(comm_, root_ ? plan(true, sim_->time() >= spec_.t_end) : Round{}), true,
            false);
      if (root_) progress();
      proto_.agree();  // rank 0: gauges, watchdog, outputs
    }
  } catch (const InstabilityError& e) {
    if (!root_) throw;
    if (opt_.progress && tty_) std::fprintf(stderr, "\n");
    diag_->flush();
    gauges_->flush();
    std::ostringstream m;
    m << e.what() << ". ";
    if (last_checkpoint_ >= 0.0)
      m << "The last checkpoint, " << ck_path_ << " (t = " << last_checkpoint_
        << " s), was taken while the run was healthy";
    else
      m << "No checkpoint was written (the run failed before the first one)";
    throw InstabilityError(m.str());
  }
}

// SIGINT/SIGTERM: everything consistent on disk at this step, then leave.
template <int D>
void Run<D>::stop_now(int sig) {
  if (root_ && opt_.progress && tty_) std::fprintf(stderr, "\n");
  round({kRound | kCheckpoint | (view_->shared_output() ? 0u : unsigned{kGather}), 0}, false, true);
  proto_.agree();
  if (!root_) throw Interrupted(sig, "stopped");
  std::ostringstream m;
  m << "stopped by "
    << (sig == SIGINT    ? "SIGINT"
        : sig == SIGTERM ? "SIGTERM"
                         : "a signal")
    << " at t = " << sim_->time() << " s, step " << sim_->steps() << "; checkpoint " << ck_path_
    << " written\ncontinue with: swell run " << spec_.file << " --restart " << out_dir_;
  throw Interrupted(sig, m.str());
}

// The progress line (stderr, unless -q; run.log always), every 2 s and at the end.
template <int D>
void Run<D>::progress() {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_progress_ <= std::chrono::seconds(2) && sim_->time() < spec_.t_end) return;
  last_progress_ = now;
  const double t_end = spec_.t_end;
  const double el = std::chrono::duration<double>(now - loop0_).count();
  const double rate = static_cast<double>(sim_->steps() - step0_) * n_total_ / std::max(el, 1e-9);
  const double eta = el / (sim_->time() - time0_) * (t_end - sim_->time());
  char line[256];
  std::snprintf(line, sizeof line,
                "t = %.4f / %.4f s | step %ld | dt %.3e s | %.2f M particle-steps/s | ETA %s",
                sim_->time(), t_end, sim_->steps(), sim_->dt(), rate / 1e6,
                format_duration(eta).c_str());
  log_.file_line(line);
  if (opt_.progress) {
    std::fprintf(stderr, "%s%s%s", tty_ ? "\r" : "", line, tty_ ? "   " : "\n");
    std::fflush(stderr);
  }
}

// What is due now (rank 0 decides; announce() tells the other ranks).
template <int D>
Round Run<D>::plan(bool after_step, bool final_state) {
  const double t = sim_->time();
  Round r{0, snapshot_};
  if (gauges_->due(t) || (after_step && gauges_->averages())) r.bits |= kGauges;
  if (after_step && watchdog_->due(sim_->steps())) r.bits |= kWatch;
  if (diag_timer_.due(t)) r.bits |= kDiag;
  if (out_timer_.due(t) || (final_state && out_timer_.next > t + 1e-12 && snapshot_ > 0))
    r.bits |= kSnapshot;
  if (ck_timer_.due(t) || final_state) r.bits |= kCheckpoint;
  if (!view_->shared_output() && (r.bits & (kSnapshot | kCheckpoint))) r.bits |= kGather;
  if ((r.bits & kGauges) && gather_everything()) r.bits |= kGather;
  if (r.bits & kGather) r.bits &= ~unsigned{kGauges};  // the whole state serves the gauges
  if (r.bits) r.bits |= kRound;
  return r;
}

// The watchdog's check (collective). On rank 0 an unstable run throws InstabilityError and a
// warning returns true; the other ranks leave quietly (rank 0 says why).
template <int D>
bool Run<D>::check_watchdog() {
  if (root_) return watchdog_->check(view_->local(), *view_);
  try {
    watchdog_->check(view_->local(), *view_);
  } catch (const InstabilityError&) {
    throw PeerFailed(3);
  }
  return false;
}

// One output round, the same on every rank: the collectives every rank makes alike (the run's
// counts, the gathers, the watchdog, the diagnostics: a failure there is every rank's); rank
// 0's own outputs (diagnostics row, gauges, from a gather the snapshot), agreed; the shared
// snapshot; the watchdog again before a checkpoint (written only while the run is healthy,
// after the step's other outputs as on one rank), rank 0's own checkpoint from a gather,
// agreed, or every rank's rows; then settle().
template <int D>
void Run<D>::round(Round r, bool after_step, bool stop) {
  if (!r.bits) return;
  const double t = sim_->time();
  RunView<D>& view = *view_;
  proto_.symmetric();
  view.reduce_counts();
  if (r.bits & kGather) view.gather();
  if (r.bits & kGauges) view.gather_region(*region_);
  const bool warned = (r.bits & kWatch) && check_watchdog();
  std::vector<double> row;
  if (r.bits & kDiag)
    row = diagnostics_row(sim_->particles(), view, sim_->steps(), sim_->dt(), up_, setup_->floor,
                          band_, spec_.dp);
  std::optional<WriteShare> share;
  if (view.shared_output() && (r.bits & (kSnapshot | kCheckpoint))) share = view.share();
  proto_.root_work();
  std::map<std::string, double> ck;
  if (root_) {
    if (warned) log_ << "  " << watchdog_->warning() << "\n" << std::flush;
    if (after_step && gauges_->averages())
      gauges_->accumulate(sim_->dt(), view.particles(), view.pressure());
    if (r.bits & kDiag) {
      diag_->write_row(t, row, std::vector<bool>(7, true));
      diag_timer_.advance(t);
    }
    if (!stop && gauges_->due(t))
      gauges_->sample(t, view.particles(), view.pressure(), view.acceleration());
    if (r.bits & kSnapshot) {
      if (!share) write_snapshot();
      if (!stop) out_timer_.advance(t);
      ++snapshot_;
      ++sum_.snapshots;
    }
    if (r.bits & kCheckpoint) {
      if (!stop && ck_timer_.due(t)) ck_timer_.advance(t);
      ck = checkpoint_schedule(share);
      diag_->flush();
      gauges_->flush();
    }
  }
  proto_.agree();
  proto_.symmetric();
  if (share && (r.bits & kSnapshot)) {
    const double t0 = omp_get_wtime();
    std::vector<PvdSeries*> pvds;
    if (root_) pvds = {&*pvd_, &*pvd_fluid_, &*pvd_bound_};
    if (!shared_snapshot<D>(out_, spec_, r.snapshot, sim_->steps(), t, sim_->particles(),
                            view.local_pressure(), body_names_, normals_, *share, comm_,
                            h5_ ? &*h5_ : nullptr, pvds))
      throw PeerFailed(1);  // rank 0 says why
    sum_.output_seconds += omp_get_wtime() - t0;
  }
  if (r.bits & kCheckpoint) {
    const double t0 = omp_get_wtime();
    const bool warned_now = check_watchdog();  // a checkpoint only of a healthy run
    proto_.root_work();
    if (root_ && warned_now) log_ << "  " << watchdog_->warning() << "\n" << std::flush;
    if (root_ && !share) write_checkpoint<D>(ck_path_, view.particles(), view.clock(), ck, tag_);
    proto_.agree();  // rank 0 wrote it (from a gather), or every rank writes its rows
    proto_.symmetric();
    if (share) {
      if (root_)
        write_checkpoint<D>(ck_path_, sim_->particles(), view.clock(), ck, tag_, &*share);
      else if (!write_checkpoint_rows<D>(ck_path_, sim_->particles(), *share))
        throw PeerFailed(1);
    }
    last_checkpoint_ = t;
    sum_.output_seconds += omp_get_wtime() - t0;
  }
  view.settle();
  proto_.root_work();
}

// A snapshot from rank 0 alone: one rank, or the particles gathered here.
template <int D>
void Run<D>::write_snapshot() {
  const double t0 = omp_get_wtime();
  RunView<D>& view = *view_;
  const auto& p = view.pressure();
  const double t = sim_->time();
  if (spec_.vtk) {
    const std::string rel = vtk_file(spec_.name, "", snapshot_, false);
    write_vtp<D>((out_ / rel).string(), view.particles(), p, ParticleFilter::All, &meta_.body_names,
                 t);
    pvd_->add(t, rel);
    if (spec_.vtk_split) {
      const std::string rf = vtk_file(spec_.name, "_fluid", snapshot_, false),
                        rb = vtk_file(spec_.name, "_boundary", snapshot_, false);
      write_vtp<D>((out_ / rf).string(), view.particles(), p, ParticleFilter::Fluid,
                   &meta_.body_names, t);
      write_vtp<D>((out_ / rb).string(), view.particles(), p, ParticleFilter::Boundary,
                   &meta_.body_names, t);
      pvd_fluid_->add(t, rf);
      pvd_bound_->add(t, rb);
    }
  }
  if (h5_) h5_->write_snapshot<D>(sim_->steps(), t, view.particles(), p);
  sum_.output_seconds += omp_get_wtime() - t0;
}

// The checkpoint's schedule: the runner's timers, the gauges' and hooks' state, the faces'
// exclusions and, on several ranks, the slabs and each rank's share of the file.
template <int D>
std::map<std::string, double> Run<D>::checkpoint_schedule(const std::optional<WriteShare>& share) {
  std::map<std::string, double> s;
  const RunView<D>& view = *view_;
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
  s["next_output"] = out_timer_.next;
  s["next_diagnostics"] = diag_timer_.next;
  s["next_checkpoint"] = ck_timer_.next;
  s["snapshot"] = snapshot_;
  gauges_->save_schedule(s);
  sim_->save_hooks(s);
  if (view.decomposed()) {
    sim_->exchange()->save(s);
    const auto& active = share ? share->active : view.layout().active;
    const auto& excluded = share ? share->excluded : view.layout().excluded;
    for (std::size_t r = 0; r < active.size(); ++r) {
      s["decomposition.active." + std::to_string(r)] = static_cast<double>(active[r]);
      s["decomposition.excluded." + std::to_string(r)] = static_cast<double>(excluded[r]);
    }
  }
  return s;
}

// The decomposition's figures (collective), then on rank 0 the summary: printed, in
// run_summary.txt, and in run_info.yaml.
template <int D>
RunSummary Run<D>::finish() {
  const auto wall1 = std::chrono::steady_clock::now();
  const double loop_s = std::chrono::duration<double>(wall1 - loop0_).count();
  // Collective (the other ranks wait in it): before anything of rank 0's own that may throw.
  const std::string decomposition =
      decomposition_report(*sim_, comm_, loop_s, sim_->steps() - step0_);
  if (!root_) return {};
  proto_.symmetric();  // the other ranks are done
  if (opt_.progress && tty_) std::fprintf(stderr, "\n");
  diag_->flush();
  gauges_->flush();

  RunSummary& sum = sum_;
  const RunView<D>& view = *view_;
  const Watchdog<D>& watchdog = *watchdog_;
  const auto& opt = opt_;
  const auto& spec = spec_;
  const std::size_t n_total = n_total_;
  const double resume_after = resume_after_;
  const std::string& out_dir = out_dir_;
  const fs::path& out = out_;
  const Provenance& prov = prov_;
  RunInfo& info = info_;
  PvdSeries& pvd = *pvd_;
  sum.wall_seconds = std::chrono::duration<double>(wall1 - wall0_).count();
  sum.steps = sim_->steps();
  sum.sim_time = sim_->time();
  const long loop_steps = sim_->steps() - step0_;
  sum.particle_steps_per_second =
      static_cast<double>(n_total) * loop_steps / std::max(loop_s, 1e-9);
  sum.excluded = view.excluded();
  sum.faces = view.excluded_faces();
  sum.excluded_fluid_fraction = watchdog.excluded_fraction();
  sum.excluded_warning = watchdog.warned();
  sum.phases = sim_->phase_times();

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
  log_ << s.str();
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
    return spec.dim == 2 ? Run<2>(spec, options, log, proto).execute()
                         : Run<3>(spec, options, log, proto).execute();
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
