// The rules by which the ranks of a run keep in step between steps: the output round rank 0
// announces after each step (Round, announce), the agreements that carry rank 0's failures to
// the others (RunProtocol), and the simulated-time schedules of the outputs (Timer). One rank:
// every call is the identity or a no-op.
#pragma once

#include <cstdint>

#include "parallel/comm.hpp"
#include "run/run.hpp"

namespace swell {

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
inline Round announce(const parallel::Comm& comm, Round r) {
  if (comm.size() == 1) return r;
  const auto v = static_cast<std::uint64_t>(comm.max(r.bits + 256.0 * r.snapshot));
  return {static_cast<unsigned>(v & 255u), static_cast<int>(v >> 8)};
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

}  // namespace swell
