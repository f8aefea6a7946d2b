// HDF5 output: one run file (metadata + particle snapshots) and crash-safe checkpoints.
//
// Snapshots are stored one HDF5 file each, written crash-safely (temporary name, fsync,
// rename), and the run file is an index rewritten the same way after each snapshot, so a kill
// at any moment loses at most the snapshot being written:
//   OUTDIR/snapshots/<stem>_<step, 10 digits>.h5   /metadata and the one snapshot
//                                                  /particles/<step>, as below
//   OUTDIR/<stem>.h5 (the run file)                /metadata and /particles/<step> for every
//                                                  snapshot, as HDF5 external links into the
//                                                  files above (h5py and h5dump follow them)
// where <stem> is the run file's name without .h5. A restart rebuilds the index from the
// snapshot files, never from the previous index.
//
// Run file layout (readable with h5py or h5dump, strings are UTF-8):
//   /                              attributes provenance_<field> for every Provenance field
//                                  (version, commit, compiler, build, command, threads, ranks,
//                                  date, host, cpu): the command that wrote this file
//   /metadata                      group; attributes case_name, case_file, version, kernel,
//                                  dim, dp, h, c0, rho0, n_fluid, n_boundary, body_names[]
//   /metadata/case_text            scalar string dataset: the case file as read
// Every dataset has a string attribute `units` (SI; "1" for counts, codes and text; in 2D
// mass is per metre of depth, "kg/m").
//   /particles/<step, 10 digits>   group; attributes time (double), step (int64), written last
//       pos (N x D double), vel (N x D float*), rho (N float*), p, mass (N double), type (N
//                                  uint8: the role, 0 fluid,
//                                  1 fixed wall, 2 moving wall, 3 floating),
//       body (N uint16), id (N uint32) over the active particles only
//       (* as stored: double in a -DSWELL_DOUBLE_STATE=ON build; solver/state/types.hpp)
//
// Checkpoint layout (a separate file, everything needed to continue a run bit for bit):
//   /               attributes dim, n_active, total, case_identity, case_name, case_file,
//                   complete (=1, written last)
//   /particles      every enabled field of ParticleSet's field table under its name (pos, vel,
//                   rho, vel_prev, rho_prev, mass, role, body, id, and pos_ref in
//                   runs with moving bodies), over the whole storage [0, total()) in the
//                   current order
//   /clock          attributes time, steps, dt, first_dt, verlet_counter,
//                   excluded_out_of_domain, excluded_non_finite, excluded_density_out_of_range
//   /schedule       datasets names (strings) and values (double), the runner's timers and
//                   the state the step hooks save (bc/ modules; names "hook.<module>.<key>")
//
// A decomposed run (several MPI ranks, issue #16) in a build with parallel HDF5 writes these
// same files from every rank at once (WriteShare): rank 0 writes everything but the particle
// rows, every rank then writes its own rows through MPI-IO (collective), rank 0 writes the
// marks that come last and renames. The file is the one the particles gathered to one process
// would give: the active particles of rank 0, 1, ... in each rank's order, then (checkpoints)
// their excluded particles in the same rank order.
//
// Every failure is a std::runtime_error naming the file and the object involved.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io/provenance.hpp"
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
  // How the file was made (the command that wrote it): root attributes of the run file and of
  // each snapshot file (provenance_version, provenance_commit, ...; see Provenance::fields).
  Provenance provenance;
};

// This rank's part in a file that every rank of a decomposed run writes together: its rank and
// every rank's particle counts, in rank order.
struct WriteShare {
  int rank = 0;
  std::vector<std::uint64_t> active, excluded;  // per rank
};

// Whether this build can write a file from several ranks at once (an MPI build linked with
// parallel HDF5, libhdf5-openmpi-dev). Without it a decomposed run gathers its particles to
// rank 0 for its output.
bool parallel_hdf5();

// The run file of a run being written: its metadata and the snapshots written so far. Each
// write_snapshot writes one snapshot file and then the index (see above); nothing stays open
// between calls.
class Hdf5RunFile {
 public:
  // Starts a new run file at `path` (replacing an existing one) and removes the snapshot files
  // an earlier run file of the same name left in the snapshots folder.
  static Hdf5RunFile create(const std::string& path, const RunMetadata& meta);

  // For a restarted run: keeps the complete snapshot files with time <= t_keep, deletes later
  // and unfinished ones, and rewrites the index listing the kept ones, so the series continues
  // without duplicates or gaps whatever state the previous index was left in. Throws if a
  // snapshot file holds a run of another dimension.
  static Hdf5RunFile open_for_append(const std::string& path, const RunMetadata& meta,
                                     double t_keep);

  // Writes the active particles [0, ps.size()) as snapshot `step`, then the index. `pressure`
  // must hold at least ps.size() values. A snapshot of the same step is replaced.
  // With `share` (rank 0 of a decomposed run): `ps` and `pressure` are rank 0's own particles
  // and every rank calls this at once, the others through write_snapshot_rows.
  template <int D>
  void write_snapshot(long step, double time, const ParticleSet<D>& ps,
                      const std::vector<double>& pressure, const WriteShare* share = nullptr);

  // The snapshot file of step `step` of the run file at `path`.
  static std::string snapshot_path(const std::string& path, long step);

  const std::string& path() const { return path_; }
  std::size_t snapshot_count() const { return entries_.size(); }

  struct Entry {
    long step = 0;
    double time = 0;
  };

 private:
  Hdf5RunFile(std::string path, RunMetadata meta);
  std::string snapshot_file(long step) const;  // relative to the run file's folder
  void write_index() const;

  std::string path_, folder_, stem_;
  RunMetadata meta_;
  std::vector<Entry> entries_;  // by step
  // Test hook (SWELL_TEST_KILL_AT=snapshot-data:N or snapshot-index:N): SIGKILL this process
  // in the N-th snapshot write, after the snapshot's (or the index's) temporary file is
  // complete and before its rename.
  int kill_point_ = 0;  // 0 none, 1 snapshot-data, 2 snapshot-index
  long kill_at_ = 0, writes_ = 0;
};

// Ranks 1..N-1 of a decomposed run: their rows of the snapshot that rank 0 writes with
// Hdf5RunFile::write_snapshot(..., share) at the same time (collective). Returns false when a
// rank failed (rank 0 then throws and says why).
template <int D>
bool write_snapshot_rows(const std::string& run_file, long step, const ParticleSet<D>& ps,
                         const std::vector<double>& pressure, const WriteShare& share);

// The folder (next to the run file) that holds its snapshot files.
std::string snapshot_folder(const std::string& run_file);

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

// What a checkpoint says about the case that wrote it (case/identity.hpp).
struct CaseTag {
  std::string identity, name, file;
};

template <int D>
struct Checkpoint {
  CaseTag tag;  // empty identity: written without one (tests, older versions)
  ParticleSet<D> particles;
  SimulationClock clock;
  std::map<std::string, double> schedule;
};

// Writes path + ".tmp", syncs it to disk, moves the previous checkpoint (if complete) to
// path + ".prev" and renames the new one over `path`. A crash at any point leaves at least
// one complete checkpoint among `path` and path + ".prev".
// With `share` (rank 0 of a decomposed run): `ps` is rank 0's own storage, and every other
// rank calls write_checkpoint_rows at the same time (collective).
template <int D>
void write_checkpoint(const std::string& path, const ParticleSet<D>& ps,
                      const SimulationClock& clock, const std::map<std::string, double>& schedule,
                      const CaseTag& tag = {}, const WriteShare* share = nullptr);

// Ranks 1..N-1: their rows of the checkpoint rank 0 writes. False when a rank failed.
template <int D>
bool write_checkpoint_rows(const std::string& path, const ParticleSet<D>& ps,
                           const WriteShare& share);

// Throws if the file is missing, unreadable, incomplete or holds another dimension. With
// `rows` (a restart on as many ranks as wrote it): only rank rows.rank's particles (its active
// rows, then its excluded ones; the counts of every rank from the checkpoint's decomposition
// record), as that rank held them.
template <int D>
Checkpoint<D> read_checkpoint(const std::string& path, const WriteShare* rows = nullptr);

// The /schedule of a checkpoint alone (small: timers, hooks' state, decomposition record).
std::map<std::string, double> read_checkpoint_schedule(const std::string& path);

// The dimension (2 or 3) of the run saved in a checkpoint.
int checkpoint_dimension(const std::string& path);

// A checkpoint's particle counts: active (the first rows) and all.
std::pair<std::uint64_t, std::uint64_t> checkpoint_counts(const std::string& path);

// `path` if it reads back completely, else path + ".prev" if that does; throws otherwise
// (the message names both files and why each was rejected). Reads one dataset at a time.
std::string latest_valid_checkpoint(const std::string& path);

// Keeps HDF5 from registering its atexit clean-up, which can crash (SIGSEGV) when a write
// failed (disk full) and files are left half-closed. Call first thing in main(); every file
// is closed by its owner before exit, and the files that matter were renamed into place only
// when complete.
void hdf5_no_atexit();

}  // namespace swell
