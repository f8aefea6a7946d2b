// The run of a set-up case (case/setup.hpp): the time loop with VTK output, diagnostics, a
// progress line and a summary (run_case, run/run.cpp). Used by the `swell` command and by
// the end-to-end tests.
#pragma once

#include <iosfwd>
#include <stdexcept>
#include <string>

#include "case/setup.hpp"
#include "case/spec.hpp"
#include "solver/time/simulation.hpp"

namespace swell {

struct RunOptions {
  std::string out_dir;          // default: out/<case name>
  int threads = 0;              // 0: OpenMP default
  bool progress = true;         // progress line on stderr
  std::ostream* log = nullptr;  // summary stream (stdout if null)
  // Continue from OUTDIR/checkpoint.h5 (or its .prev if the last one is damaged) up to the
  // case's time.end; outputs written after the checkpoint time are replaced.
  bool restart = false;
  // Replace the run an output folder already holds (else such a folder is refused).
  bool overwrite = false;
  // Several MPI ranks: the slab bounds are balanced by particle count every this many steps
  // (0: never).
  long rebalance_every = 100;
};

// Thrown on the other ranks of a decomposed run when rank 0 failed in its own work (files,
// gauges, watchdog): rank 0 reports; the others leave quietly with the same exit code.
class PeerFailed : public std::runtime_error {
 public:
  explicit PeerFailed(int code)
      : std::runtime_error("rank 0 stopped the run (its message says why)"), code_(code) {}
  int exit_code() const { return code_; }

 private:
  int code_;
};

struct RunSummary {
  std::size_t fluid = 0, boundary = 0;
  long steps = 0;
  double sim_time = 0.0;
  double wall_seconds = 0.0;
  double particle_steps_per_second = 0.0;
  ExclusionCounts excluded;
  FaceExclusions faces;                // out of the domain, by face and time
  double excluded_fluid_fraction = 0;  // of the initial fluid mass
  bool excluded_warning = false;       // it passed watchdog.warn_excluded
  PhaseTimes phases;
  double output_seconds = 0.0;
  int snapshots = 0;
  double restarted_from = -1.0;  // checkpoint time when restarted
};

// Runs the case to time.end, writing OUTDIR/<name>.pvd + OUTDIR/vtk/*.vtp, OUTDIR/<name>.h5
// (snapshots + metadata), OUTDIR/checkpoint.h5, OUTDIR/gauges_<kind>.csv and
// OUTDIR/diagnostics.csv. Holds OUTDIR/.swell.lock while it runs. Throws std::invalid_argument
// for a folder in use or holding another run (unless overwrite), or a checkpoint of another
// case; Interrupted (run/stop_signals.hpp) after SIGINT/SIGTERM; InstabilityError if the run blows
// up (the last checkpoint written before stays valid).
// Under mpirun with N > 1 ranks every rank calls it: the particles are split into slabs
// (parallel/halo.hpp) and rank 0 alone writes (its summary covers the whole run; the others
// return an empty one).
RunSummary run_case(const CaseSpec& spec, const RunOptions& options);

}  // namespace swell
