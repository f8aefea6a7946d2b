// HDF5 output: one run file (metadata + particle snapshots) and crash-safe checkpoints.
//
// Run file layout (readable with h5py or h5dump, strings are UTF-8):
//   /metadata                      group; attributes case_name, case_file, version, kernel,
//                                  dim, dp, h, c0, rho0, n_fluid, n_boundary, body_names[]
//   /metadata/case_text            scalar string dataset: the case file as read
//   /particles/<step, 10 digits>   group; attributes time (double), step (int64), written last
//       pos, vel (N x D double), rho, p, mass (N double), type (N uint8: the role, 0 fluid,
//                                  1 fixed wall, 2 moving wall, 3 floating),
//       body (N uint16), id (N uint32) over the active particles only
//
// Checkpoint layout (a separate file, everything needed to continue a run bit for bit):
//   /               attributes dim, n_active, total, complete (=1, written last)
//   /particles      every enabled field of ParticleSet's field table under its name (pos, vel,
//                   rho, pos_prev, vel_prev, rho_prev, mass, role, body, id, and pos_ref in
//                   runs with moving bodies), over the whole storage [0, total()) in the
//                   current order
//   /clock          attributes time, steps, dt, first_dt, verlet_counter,
//                   excluded_out_of_domain, excluded_non_finite, excluded_density_out_of_range
//   /schedule       datasets names (strings) and values (double), the runner's timers and
//                   the state the step hooks save (bc/ modules; names "hook.<module>.<key>")
//
// Every failure is a std::runtime_error naming the file and the object involved.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "solver/state/particle_set.hpp"
#include "solver/time/clock.hpp"
#include "swell/version.hpp"

namespace swell {

struct RunMetadata {
  std::string case_name, case_file, case_text, version = SWELL_VERSION;
  int dim = 2;
  double dp = 0, h = 0, c0 = 0, rho0 = 0;
  std::string kernel;
  std::uint64_t n_fluid = 0, n_boundary = 0;
  std::vector<std::string> body_names;  // index = body id
};

// One open run file. Movable, not copyable; the file is closed by the destructor.
class Hdf5RunFile {
 public:
  // Creates `path` (truncating any existing file) and writes `meta` to /metadata.
  static Hdf5RunFile create(const std::string& path, const RunMetadata& meta);

  // For a restarted run: opens `path` and deletes the snapshots later than t_keep (and any
  // snapshot left incomplete by a crash), so the series continues without duplicates. If
  // the file is missing, a fresh one is created; if it cannot be opened (corrupt after a
  // crash), it is renamed to path + ".corrupt" and a fresh one is created. In both cases
  // *recreated is set to true. Throws if the file holds a run of another dimension.
  static Hdf5RunFile open_for_append(const std::string& path, const RunMetadata& meta,
                                     double t_keep, bool* recreated = nullptr);

  Hdf5RunFile(Hdf5RunFile&& other) noexcept;
  Hdf5RunFile& operator=(Hdf5RunFile&& other) noexcept;
  Hdf5RunFile(const Hdf5RunFile&) = delete;
  Hdf5RunFile& operator=(const Hdf5RunFile&) = delete;
  ~Hdf5RunFile();

  // Writes the active particles [0, ps.size()) as /particles/<step>, then flushes the file.
  // `pressure` must hold at least ps.size() values. A snapshot of the same step already in
  // the file is replaced.
  template <int D>
  void write_snapshot(long step, double time, const ParticleSet<D>& ps,
                      const std::vector<double>& pressure);

  // Closes now, reporting errors (the destructor cannot). Safe to call twice.
  void close();
  bool is_open() const { return file_ >= 0; }
  const std::string& path() const { return path_; }

 private:
  Hdf5RunFile(std::string path, std::int64_t file) : path_(std::move(path)), file_(file) {}

  std::string path_;
  std::int64_t file_ = -1;  // hid_t (an int64_t since HDF5 1.10); -1 when closed
};

RunMetadata read_metadata(const std::string& path);

struct SnapshotInfo {
  std::string group;  // full path in the file, "/particles/0000000100"
  long step = 0;
  double time = 0;
};

// Complete snapshots of a run file, sorted by time (then step).
std::vector<SnapshotInfo> list_snapshots(const std::string& path);

template <int D>
struct SnapshotData {
  long step = 0;
  double time = 0;
  std::vector<Vec<D>> pos, vel;
  std::vector<double> rho, p, mass;
  std::vector<std::uint8_t> type;
  std::vector<std::uint16_t> body;
  std::vector<std::uint32_t> id;
};

template <int D>
SnapshotData<D> read_snapshot(const std::string& path, const SnapshotInfo& info);

template <int D>
struct Checkpoint {
  ParticleSet<D> particles;
  SimulationClock clock;
  std::map<std::string, double> schedule;
};

// Writes path + ".tmp", syncs it to disk, moves the previous checkpoint (if complete) to
// path + ".prev" and renames the new one over `path`. A crash at any point leaves at least
// one complete checkpoint among `path` and path + ".prev".
template <int D>
void write_checkpoint(const std::string& path, const ParticleSet<D>& ps,
                      const SimulationClock& clock, const std::map<std::string, double>& schedule);

// Throws if the file is missing, unreadable, incomplete or holds another dimension.
template <int D>
Checkpoint<D> read_checkpoint(const std::string& path);

// The dimension (2 or 3) of the run saved in a checkpoint.
int checkpoint_dimension(const std::string& path);

// `path` if it reads back completely, else path + ".prev" if that does; throws otherwise
// (the message names both files and why each was rejected).
std::string latest_valid_checkpoint(const std::string& path);

}  // namespace swell
