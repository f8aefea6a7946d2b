#include "io/hdf5_file.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include "io/hdf5_objects.hpp"

namespace swell {
namespace {

using namespace hdf5;
namespace fs = std::filesystem;

static_assert(std::is_same_v<hid_t, std::int64_t>, "Hdf5RunFile keeps its hid_t in an int64_t");
static_assert(std::is_same_v<long, std::int64_t> && std::is_same_v<std::size_t, std::uint64_t>,
              "steps (long) and counts (size_t) are stored as 64-bit integers");

// Snapshot times within this of t_keep are kept by open_for_append.
constexpr double kTimeSlack = 1e-12;

std::string snapshot_name(long step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%010ld", step);
  return buf;
}

// Every attribute of /metadata, listed once for writing and reading.
template <class M, class Fn>
void metadata_fields(M& m, Fn&& fn) {
  fn("case_name", m.case_name);
  fn("case_file", m.case_file);
  fn("version", m.version);
  fn("kernel", m.kernel);
  fn("dim", m.dim);
  fn("dp", m.dp);
  fn("h", m.h);
  fn("c0", m.c0);
  fn("rho0", m.rho0);
  fn("n_fluid", m.n_fluid);
  fn("n_boundary", m.n_boundary);
  fn("body_names", m.body_names);
}

// Every SimulationClock field, as attributes of /clock in a checkpoint.
template <class C, class Fn>
void clock_fields(C& c, Fn&& fn) {
  fn("time", c.time);
  fn("steps", c.steps);
  fn("dt", c.dt);
  fn("first_dt", c.first_dt);
  fn("verlet_counter", c.verlet_counter);
  fn("excluded_out_of_domain", c.excluded.out_of_domain);
  fn("excluded_non_finite", c.excluded.non_finite);
  fn("excluded_density_out_of_range", c.excluded.density_out_of_range);
}

// Every enabled field of the ParticleSet table (for_each_field), as datasets of /particles.
template <class PS, class Fn>
void checkpoint_arrays(PS& ps, Fn&& fn) {
  // Every enabled field of the table, under its own name (optional fields only when in use).
  ps.for_each_field([&](const FieldInfo& f, auto& a) {
    if (ps.enabled(f)) fn(f.name, a);
  });
}

// The units attribute of dataset `name` in `g` (a string, SI; "1" for counts, codes, text).
void write_units(const Loc& g, const char* name, const std::string& units) {
  Handle ds(H5Dopen2(g.id, name, H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail_h5(g.file, g.dataset(name), "cannot be opened to set its units");
  write_strings(Loc{ds.get(), g.file, g.child(name)}, "units", {units}, true, false);
}

// Units of a snapshot dataset (by its name in the file) in a run of dimension `dim`: 2D
// quantities are per metre of depth where they are extensive (mass).
std::string snapshot_units(const std::string& name, int dim) {
  if (name == "pos" || name == "normal") return "m";
  if (name == "vel") return "m/s";
  if (name == "rho") return "kg/m^3";
  if (name == "p") return "Pa";
  if (name == "mass") return dim == 2 ? "kg/m" : "kg";
  return "1";  // type, body, id
}

void write_metadata(const Loc& root, const RunMetadata& m) {
  for (const auto& [key, value] : m.provenance.fields())
    write_field(root, ("provenance_" + key).c_str(), value);
  Handle g = create_group(root, "metadata");
  const Loc meta = root.at(g.get(), "metadata");
  metadata_fields(m, [&](const char* name, const auto& v) { write_field(meta, name, v); });
  // A dataset, not an attribute: case files can exceed the 64 KiB attribute limit.
  write_strings(meta, "case_text", {m.case_text}, true, true);
  write_units(meta, "case_text", "1");
}

RunMetadata read_metadata_group(const Loc& root) {
  Handle g = open_group(root, "metadata");
  const Loc meta = root.at(g.get(), "metadata");
  RunMetadata m;
  metadata_fields(m, [&](const char* name, auto& v) { read_field(meta, name, v); });
  // Files written before provenance existed have none: the fields stay empty.
  Provenance& p = m.provenance;
  for (auto [key, to] : {std::pair<const char*, std::string*>{"version", &p.version},
                         {"commit", &p.commit},
                         {"compiler", &p.compiler},
                         {"build", &p.build},
                         {"command", &p.command},
                         {"date", &p.date},
                         {"host", &p.host},
                         {"cpu", &p.cpu}}) {
    const std::string name = std::string("provenance_") + key;
    if (has_attr(root, name.c_str())) read_field(root, name.c_str(), *to);
  }
  for (auto [key, to] :
       {std::pair<const char*, int*>{"threads", &p.threads}, {"ranks", &p.ranks}}) {
    const std::string name = std::string("provenance_") + key;
    if (has_attr(root, name.c_str()))
      *to = std::stoi(read_strings(root, name.c_str(), false).at(0));
  }
  const auto text = read_strings(meta, "case_text", true);
  if (text.size() != 1) fail(root.file, meta.dataset("case_text"), "is not a single string");
  m.case_text = text[0];
  return m;
}

void rename_or_fail(const std::string& from, const std::string& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) throw std::runtime_error("cannot rename '" + from + "' to '" + to + "': " + ec.message());
}

// Forces a file's (or a folder's) contents to disk.
void sync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | (directory ? O_DIRECTORY : 0));
  if (fd < 0) throw std::runtime_error("cannot open '" + path + "' to sync it: " + strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  // Some file systems cannot sync a folder (EINVAL); the rename is then as durable as they allow.
  if (rc != 0 && !(directory && err == EINVAL))
    throw std::runtime_error("cannot sync '" + path + "' to disk: " + strerror(err));
}

bool checkpoint_is_complete(const std::string& path) {
  Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) return false;
  const Loc root{f.get(), path, "/"};
  try {
    return has_attr(root, "complete") && read_attr<std::int32_t>(root, "complete") == 1;
  } catch (const std::runtime_error&) {
    return false;
  }
}

// Removes `path` if it exists; failures are ignored (used on error paths and for stale files).
void remove_quietly(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

// Writes an HDF5 file crash-safely: `fill` writes into path + ".tmp", which is then closed,
// synced and renamed over `path` (and the folder synced). On any failure the temporary file
// is removed and `path` is left as it was. `before_rename` runs just before the rename.
template <class Fill, class Hook>
void write_h5_atomically(const std::string& path, Fill&& fill, Hook&& before_rename) {
  const std::string tmp = path + ".tmp";
  try {
    {
      Handle f(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
      if (!f.valid()) fail_h5(tmp, "", "cannot be created");
      fill(Loc{f.get(), tmp, "/"});
      if (H5Fflush(f.get(), H5F_SCOPE_GLOBAL) < 0) fail_h5(tmp, "", "cannot be flushed");
      if (!f.close()) fail_h5(tmp, "", "cannot be closed");
    }
    sync_path(tmp, false);
    before_rename();
    rename_or_fail(tmp, path);
  } catch (...) {
    remove_quietly(tmp);
    throw;
  }
  const fs::path dir = fs::path(path).parent_path();
  sync_path(dir.empty() ? "." : dir.string(), true);
}

// ---- Files several ranks write (parallel HDF5) ---------------------------------------------

// The offsets of this rank's rows in a shared file: its active rows start after the lower
// ranks' active ones, its excluded rows after every active row and the lower ranks' excluded.
struct ShareRows {
  std::uint64_t active_first = 0, active_total = 0, excluded_first = 0, total = 0;
};

ShareRows share_rows(const WriteShare& w) {
  ShareRows r;
  for (std::size_t k = 0; k < w.active.size(); ++k) {
    if (static_cast<int>(k) < w.rank) r.active_first += w.active[k];
    if (static_cast<int>(k) < w.rank) r.excluded_first += w.excluded[k];
    r.active_total += w.active[k];
    r.total += w.active[k] + w.excluded[k];
  }
  r.excluded_first += r.active_total;
  return r;
}

// A rank whose collective write failed must still make every later collective call the others
// make (or they wait for it forever): run() keeps the first failure and goes on, rethrow()
// reports it once all the calls are made.
class CollectiveErrors {
 public:
  template <class Fn>
  void run(Fn&& fn) {
    try {
      fn();
    } catch (const std::exception& e) {
      if (first_.empty()) first_ = e.what();
    }
  }
  void rethrow() const {
    if (!first_.empty()) throw std::runtime_error(first_);
  }

 private:
  std::string first_;
};

// Logical AND of `ok` over every rank (collective); the flag itself on one process.
bool all_ranks_ok(bool ok) {
#ifdef SWELL_PARALLEL_HDF5
  int mine = ok ? 1 : 0, all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return all == 1;
#else
  return ok;
#endif
}

// Every rank writes its rows (`rows(root, dxpl)`) into the existing file `tmp`, opened through
// MPI-IO with collective transfers. Returns what went wrong on this rank ("" if nothing).
// Test hook (SWELL_TEST_FAIL_ROWS=R): rank R reports its rows as failed once it has made every
// collective call, as a rank whose disk filled up in the middle of a write would.
bool fail_rows_for_test(int rank) {
  const char* v = std::getenv("SWELL_TEST_FAIL_ROWS");
  return v && *v && std::atoi(v) == rank;
}

template <class Rows>
std::string write_rows_shared(const std::string& tmp, int rank, Rows&& rows) {
#ifdef SWELL_PARALLEL_HDF5
  try {
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    if (H5Pset_fapl_mpio(fapl.get(), MPI_COMM_WORLD, MPI_INFO_NULL) < 0)
      fail_h5(tmp, "", "cannot be set up for MPI-IO");
    Handle f(H5Fopen(tmp.c_str(), H5F_ACC_RDWR, fapl.get()), H5Fclose);
    if (!all_ranks_ok(f.valid())) {
      if (!f.valid()) fail_h5(tmp, "", "cannot be opened on this rank (MPI-IO)");
      return "HDF5 file '" + tmp + "': another rank could not open it (MPI-IO)";
    }
    Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
    H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE);
    CollectiveErrors errors;
    errors.run([&] { rows(Loc{f.get(), tmp, "/"}, dxpl.get()); });
    // Every rank's rows on disk (MPI_File_sync) before rank 0 marks the file complete.
    const bool flushed = H5Fflush(f.get(), H5F_SCOPE_GLOBAL) >= 0;
    const bool closed = f.close();
    errors.rethrow();
    if (!flushed || !closed) fail_h5(tmp, "", "cannot be synced and closed after the rows");
    if (fail_rows_for_test(rank))
      fail(tmp, "", "rank " + std::to_string(rank) + " failed its rows (SWELL_TEST_FAIL_ROWS)");
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
#else
  (void)rows;
  (void)rank;
  return "HDF5 file '" + tmp + "': this build has no parallel HDF5 to write it from several ranks";
#endif
}

// Writes an HDF5 file that every rank fills (`share`) crash-safely, as write_h5_atomically does
// for one process: rank 0 writes `skeleton` (everything but the particle rows) into
// path + ".tmp"; every rank writes its rows (`rows`, collective); rank 0 writes `finish` (the
// marks that say the file is complete), syncs the file, runs before_rename, renames it over
// `path` and runs `after`. Each of the three ends with an agreement, so no rank waits in a
// collective another has left: when any rank failed, rank 0 removes the temporary file and
// throws (its own message, or says which rank failed; that rank prints its own), the others
// return false. Every rank returns or throws at the same point.
template <class Skeleton, class Rows, class Finish, class Hook, class After>
bool write_h5_shared(const std::string& path, const WriteShare& share, Skeleton&& skeleton,
                     Rows&& rows, Finish&& finish, Hook&& before_rename, After&& after) {
  const std::string tmp = path + ".tmp";
  const bool root = share.rank == 0;
  std::string err;
  if (root) {
    try {
      Handle f(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
      if (!f.valid()) fail_h5(tmp, "", "cannot be created");
      skeleton(Loc{f.get(), tmp, "/"});
      if (!f.close()) fail_h5(tmp, "", "cannot be closed");
    } catch (const std::exception& e) {
      err = e.what();
    }
  }
  if (!all_ranks_ok(err.empty())) {
    if (!root) return false;
    remove_quietly(tmp);
    throw std::runtime_error(err);
  }
  err = write_rows_shared(tmp, share.rank, rows);
  if (!all_ranks_ok(err.empty())) {
    if (!root) {
      if (!err.empty()) std::fprintf(stderr, "swell (rank %d): %s\n", share.rank, err.c_str());
      return false;
    }
    remove_quietly(tmp);
    throw std::runtime_error(err.empty() ? "HDF5 file '" + tmp +
                                               "': another rank could not write its particles "
                                               "(that rank's message is above)"
                                         : err);
  }
  if (root) {
    try {
      {
        Handle f(H5Fopen(tmp.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
        if (!f.valid()) fail_h5(tmp, "", "cannot be opened to complete it");
        finish(Loc{f.get(), tmp, "/"});
        if (!f.close()) fail_h5(tmp, "", "cannot be closed");
      }
      sync_path(tmp, false);
      before_rename();
      rename_or_fail(tmp, path);
      const fs::path dir = fs::path(path).parent_path();
      sync_path(dir.empty() ? "." : dir.string(), true);
      after();
    } catch (const std::exception& e) {
      err = e.what();
      remove_quietly(tmp);
    }
  }
  if (!all_ranks_ok(err.empty())) {
    if (!root) return false;
    throw std::runtime_error(err);
  }
  return true;
}

// "snapshot-data:3" -> {1, 3}; "snapshot-index:2" -> {2, 2}; anything else: no hook.
std::pair<int, long> kill_hook_from_env() {
  const char* v = std::getenv("SWELL_TEST_KILL_AT");
  if (!v) return {0, 0};
  const std::string s(v);
  const auto colon = s.find(':');
  if (colon == std::string::npos) return {0, 0};
  const std::string point = s.substr(0, colon);
  const long n = std::atol(s.c_str() + colon + 1);
  if (n <= 0) return {0, 0};
  if (point == "snapshot-data") return {1, n};
  if (point == "snapshot-index") return {2, n};
  return {0, 0};
}

}  // namespace

bool parallel_hdf5() {
#ifdef SWELL_PARALLEL_HDF5
  return true;
#else
  return false;
#endif
}

// ---- Run file -----------------------------------------------------------------------------

std::string snapshot_folder(const std::string& run_file) {
  return (fs::path(run_file).parent_path() / "snapshots").string();
}

Hdf5RunFile::Hdf5RunFile(std::string path, RunMetadata meta)
    : path_(std::move(path)), meta_(std::move(meta)) {
  folder_ = snapshot_folder(path_);
  stem_ = fs::path(path_).stem().string();
  std::tie(kill_point_, kill_at_) = kill_hook_from_env();
}

std::string Hdf5RunFile::snapshot_file(long step) const {
  return "snapshots/" + stem_ + "_" + snapshot_name(step) + ".h5";
}

namespace {

// The step of a snapshot file of run `stem` ("<stem>_0000000100.h5" or that + ".tmp"), or -1.
long snapshot_file_step(const std::string& file, const std::string& stem, bool* tmp) {
  std::string f = file;
  *tmp = f.ends_with(".tmp");
  if (*tmp) f.resize(f.size() - 4);
  const std::string head = stem + "_";
  if (!f.starts_with(head) || !f.ends_with(".h5") || f.size() != head.size() + 10 + 3) return -1;
  long step = 0;
  for (std::size_t i = head.size(); i < head.size() + 10; ++i) {
    if (f[i] < '0' || f[i] > '9') return -1;
    step = step * 10 + (f[i] - '0');
  }
  return step;
}

}  // namespace

Hdf5RunFile Hdf5RunFile::create(const std::string& path, const RunMetadata& meta) {
  return open_for_append(path, meta, -std::numeric_limits<double>::infinity());
}

Hdf5RunFile Hdf5RunFile::open_for_append(const std::string& path, const RunMetadata& meta,
                                         double t_keep) {
  QuietErrors quiet;
  Hdf5RunFile run(path, meta);
  std::error_code ec;
  fs::create_directories(run.folder_, ec);
  if (ec) fail(run.folder_, "", "cannot create the snapshots folder: " + ec.message());
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(run.folder_, ec))
    names.push_back(e.path().filename().string());
  if (ec) fail(run.folder_, "", "cannot list the snapshots folder: " + ec.message());
  std::sort(names.begin(), names.end());
  for (const auto& name : names) {
    bool tmp = false;
    const long step = snapshot_file_step(name, run.stem_, &tmp);
    if (step < 0) continue;  // not one of this run's files
    const std::string file = (fs::path(run.folder_) / name).string();
    bool keep = false;
    double time = 0.0;
    if (!tmp) {
      // An unreadable snapshot file can only come from outside interference (every file is
      // renamed into place once complete); it is treated as not written.
      int dim = 0;
      try {
        dim = read_metadata(file).dim;
        const auto list = list_snapshots(file);
        if (list.size() == 1 && list[0].step == step) {
          time = list[0].time;
          keep = time <= t_keep + kTimeSlack;
        }
      } catch (const std::runtime_error&) {
        keep = false;
      }
      if (dim != 0 && dim != meta.dim)
        fail(file, "",
             "holds a " + std::to_string(dim) + "D run; cannot append " + std::to_string(meta.dim) +
                 "D snapshots");
    }
    if (keep) {
      run.entries_.push_back({step, time});
    } else {
      fs::remove(file, ec);
      if (ec) fail(file, "", "cannot remove this stale snapshot file: " + ec.message());
    }
  }
  run.write_index();
  return run;
}

void Hdf5RunFile::write_index() const {
  write_h5_atomically(
      path_,
      [&](const Loc& root) {
        write_metadata(root, meta_);
        Handle pg = create_group(root, "particles");
        for (const Entry& e : entries_) {
          const std::string name = snapshot_name(e.step);
          const std::string target = "/particles/" + name;
          if (H5Lcreate_external(snapshot_file(e.step).c_str(), target.c_str(), pg.get(),
                                 name.c_str(), H5P_DEFAULT, H5P_DEFAULT) < 0)
            fail_h5(root.file, "link '/particles/" + name + "'", "cannot be created");
        }
      },
      [&] {
        if (kill_point_ == 2 && writes_ == kill_at_) std::raise(SIGKILL);
      });
}

std::string Hdf5RunFile::snapshot_path(const std::string& path, long step) {
  const fs::path p(path);
  return (p.parent_path() / "snapshots" / (p.stem().string() + "_" + snapshot_name(step) + ".h5"))
      .string();
}

namespace {

// The datasets of a snapshot: the fields of the table that have a snapshot name, then the
// pressure. fn(name, array) in that order, on every rank alike.
template <int D, class Fn>
void snapshot_arrays(const ParticleSet<D>& ps, const std::vector<double>& pressure, Fn&& fn) {
  ps.for_each_field([&](const FieldInfo& f, const auto& a) {
    if (f.snapshot && ps.enabled(f)) fn(f.snapshot, a);
  });
  fn("p", pressure);
}

// A snapshot file's metadata and group /particles/<name>; with `rows` (one process) its
// datasets written, else (several ranks) created for `n` rows, storage allocated, to be filled
// by snapshot_rows.
template <int D>
void snapshot_skeleton(const Loc& root, const RunMetadata& meta, const std::string& name,
                       const ParticleSet<D>& ps, const std::vector<double>& pressure, std::size_t n,
                       bool rows) {
  write_metadata(root, meta);
  Handle pg = create_group(root, "particles");
  const Loc particles = root.at(pg.get(), "particles");
  Handle g = create_group(particles, name);
  const Loc snap = particles.at(g.get(), name);
  snapshot_arrays(ps, pressure, [&](const char* field, const auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if (rows)
      write_column(snap, field, a, n, true);
    else
      create_column<T>(snap, field, n, true, true);
    write_units(snap, field, snapshot_units(field, D));
  });
}

// Attributes last: a group without them was cut short and is skipped by readers.
void snapshot_finish(const Loc& root, const std::string& name, long step, double time) {
  const std::string group = "/particles/" + name;
  Handle g(H5Gopen2(root.id, group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail_h5(root.file, "group '" + group + "'", "cannot be opened");
  const Loc snap{g.get(), root.file, group};
  write_attr(snap, "time", time);
  write_attr<std::int64_t>(snap, "step", step);
}

// This rank's rows of snapshot `name` (collective).
template <int D>
void snapshot_rows(const Loc& root, hid_t dxpl, const std::string& name, const ParticleSet<D>& ps,
                   const std::vector<double>& pressure, const WriteShare& share) {
  const std::string group = "/particles/" + name;
  Handle g(H5Gopen2(root.id, group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!all_ranks_ok(g.valid())) fail(root.file, "group '" + group + "'", "cannot be opened");
  const Loc snap{g.get(), root.file, group};
  const std::uint64_t first = share_rows(share).active_first;
  CollectiveErrors errors;
  snapshot_arrays(ps, pressure, [&](const char* field, const auto& a) {
    errors.run([&] { write_rows(snap, field, a, 0, ps.size(), first, dxpl, all_ranks_ok); });
  });
  errors.rethrow();
}

void check_pressure(const std::string& file, const std::string& name, std::size_t have,
                    std::size_t n) {
  if (have < n)
    fail(file, "group '/particles/" + name + "'",
         "pressure has " + std::to_string(have) + " values for " + std::to_string(n) +
             " active particles");
}

}  // namespace

template <int D>
void Hdf5RunFile::write_snapshot(long step, double time, const ParticleSet<D>& ps,
                                 const std::vector<double>& pressure, const WriteShare* share) {
  QuietErrors quiet;
  const std::string name = snapshot_name(step);
  const std::string file = snapshot_path(path_, step);
  if (!share) check_pressure(file, name, pressure.size(), ps.size());
  ++writes_;
  auto hook = [&] {
    if (kill_point_ == 1 && writes_ == kill_at_) std::raise(SIGKILL);
  };
  auto add_entry = [&] {
    auto it = std::find_if(entries_.begin(), entries_.end(),
                           [&](const Entry& e) { return e.step >= step; });
    if (it != entries_.end() && it->step == step)
      it->time = time;
    else
      entries_.insert(it, {step, time});
    write_index();
  };
  if (share) {
    write_h5_shared(
        file, *share,
        [&](const Loc& root) {
          // (checked here: a failure before the first agreement would leave the others waiting)
          check_pressure(file, name, pressure.size(), ps.size());
          snapshot_skeleton(root, meta_, name, ps, pressure, share_rows(*share).active_total,
                            false);
        },
        [&](const Loc& root, hid_t dxpl) { snapshot_rows(root, dxpl, name, ps, pressure, *share); },
        [&](const Loc& root) { snapshot_finish(root, name, step, time); }, hook, add_entry);
    return;
  }
  write_h5_atomically(
      file,
      [&](const Loc& root) {
        snapshot_skeleton(root, meta_, name, ps, pressure, ps.size(), true);
        snapshot_finish(root, name, step, time);
      },
      hook);
  add_entry();
}

template <int D>
bool write_snapshot_rows(const std::string& run_file, long step, const ParticleSet<D>& ps,
                         const std::vector<double>& pressure, const WriteShare& share) {
  QuietErrors quiet;
  const std::string name = snapshot_name(step);
  const std::string file = Hdf5RunFile::snapshot_path(run_file, step);
  return write_h5_shared(
      file, share, [](const Loc&) {},
      [&](const Loc& root, hid_t dxpl) { snapshot_rows(root, dxpl, name, ps, pressure, share); },
      [](const Loc&) {}, [] {}, [] {});
}

RunMetadata read_metadata(const std::string& path) {
  QuietErrors quiet;
  Handle f = open_file(path, H5F_ACC_RDONLY);
  return read_metadata_group(Loc{f.get(), path, "/"});
}

std::vector<SnapshotInfo> list_snapshots(const std::string& path) {
  QuietErrors quiet;
  Handle f = open_file(path, H5F_ACC_RDONLY);
  const Loc root{f.get(), path, "/"};
  Handle pg = open_group(root, "particles");
  const Loc particles = root.at(pg.get(), "particles");
  std::vector<SnapshotInfo> out;
  for (const auto& name : child_names(particles)) {
    Handle g(H5Gopen2(pg.get(), name.c_str(), H5P_DEFAULT), H5Gclose);
    if (!g.valid()) continue;
    const Loc snap = particles.at(g.get(), name);
    if (!has_attr(snap, "time") || !has_attr(snap, "step")) continue;  // cut short by a crash
    out.push_back({snap.path, static_cast<long>(read_attr<std::int64_t>(snap, "step")),
                   read_attr<double>(snap, "time")});
  }
  std::stable_sort(out.begin(), out.end(), [](const SnapshotInfo& a, const SnapshotInfo& b) {
    return a.time < b.time || (a.time == b.time && a.step < b.step);
  });
  return out;
}

template <int D>
SnapshotData<D> read_snapshot(const std::string& path, const SnapshotInfo& info) {
  QuietErrors quiet;
  Handle f = open_file(path, H5F_ACC_RDONLY);
  const std::string group = info.group.starts_with('/') ? info.group : "/particles/" + info.group;
  Handle g(H5Gopen2(f.get(), group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail_h5(path, "group '" + group + "'", "cannot be opened");
  const Loc snap{g.get(), path, group};
  SnapshotData<D> s;
  s.step = static_cast<long>(read_attr<std::int64_t>(snap, "step"));
  s.time = read_attr<double>(snap, "time");
  const std::size_t n = read_column(snap, "id", kAnyRows, s.id);
  read_column(snap, "pos", n, s.pos);
  read_column(snap, "vel", n, s.vel);
  read_column(snap, "rho", n, s.rho);
  read_column(snap, "p", n, s.p);
  read_column(snap, "mass", n, s.mass);
  read_column(snap, "type", n, s.type);
  read_column(snap, "body", n, s.body);
  return s;
}

// ---- Checkpoints --------------------------------------------------------------------------

namespace {

// A checkpoint but its particle rows (several ranks: datasets of `total` rows, allocated) or
// with them (one process).
template <int D>
void checkpoint_skeleton(const Loc& root, const ParticleSet<D>& ps, const SimulationClock& clock,
                         const std::map<std::string, double>& schedule, const CaseTag& tag,
                         std::uint64_t n_active, std::uint64_t total, bool rows) {
  write_attr<std::int32_t>(root, "dim", D);
  write_attr<std::uint64_t>(root, "n_active", n_active);
  write_attr<std::uint64_t>(root, "total", total);
  write_field(root, "case_identity", tag.identity);
  write_field(root, "case_name", tag.name);
  write_field(root, "case_file", tag.file);
  {
    Handle g = create_group(root, "particles");
    const Loc p = root.at(g.get(), "particles");
    checkpoint_arrays(ps, [&](const char* name, const auto& v) {
      using T = typename std::decay_t<decltype(v)>::value_type;
      if (rows)
        write_column(p, name, v, total, false);
      else
        create_column<T>(p, name, total, false, true);
    });
  }
  {
    Handle g = create_group(root, "clock");
    const Loc c = root.at(g.get(), "clock");
    clock_fields(clock, [&](const char* name, const auto& v) { write_field(c, name, v); });
  }
  {
    Handle g = create_group(root, "schedule");
    const Loc s = root.at(g.get(), "schedule");
    std::vector<std::string> names;
    std::vector<double> values;
    for (const auto& [name, value] : schedule) {
      names.push_back(name);
      values.push_back(value);
    }
    write_strings(s, "names", names, false, true);
    write_column(s, "values", values, values.size(), false);
  }
}

// Last: a file without this mark was cut short and is never restarted from.
void checkpoint_finish(const Loc& root) {
  write_attr<std::int32_t>(root, "complete", 1);
}

// This rank's rows of a checkpoint (collective): its active particles, then its excluded ones.
template <int D>
void checkpoint_rows(const Loc& root, hid_t dxpl, const ParticleSet<D>& ps,
                     const WriteShare& share) {
  Handle g(H5Gopen2(root.id, "particles", H5P_DEFAULT), H5Gclose);
  if (!all_ranks_ok(g.valid())) fail(root.file, "group '/particles'", "cannot be opened");
  const Loc p = root.at(g.get(), "particles");
  const ShareRows r = share_rows(share);
  CollectiveErrors errors;
  checkpoint_arrays(ps, [&](const char* name, const auto& v) {
    errors.run([&] { write_rows(p, name, v, 0, ps.n_active, r.active_first, dxpl, all_ranks_ok); });
    errors.run([&] {
      write_rows(p, name, v, ps.n_active, ps.total() - ps.n_active, r.excluded_first, dxpl,
                 all_ranks_ok);
    });
  });
  errors.rethrow();
}

template <int D>
void check_consistent(const std::string& path, const ParticleSet<D>& ps) {
  const std::size_t total = ps.total();
  bool consistent = ps.n_active <= total;
  checkpoint_arrays(ps, [&](const char*, const auto& v) { consistent &= v.size() == total; });
  if (!consistent) fail(path, "", "cannot save a particle set whose arrays differ in size");
}

}  // namespace

template <int D>
void write_checkpoint(const std::string& path, const ParticleSet<D>& ps,
                      const SimulationClock& clock, const std::map<std::string, double>& schedule,
                      const CaseTag& tag, const WriteShare* share) {
  QuietErrors quiet;
  if (!share) check_consistent(path, ps);
  const std::string prev = path + ".prev";
  // Keep the previous checkpoint as .prev through a hard link, so `path` names a complete
  // checkpoint at every moment; the rename then replaces it atomically. An incomplete file at
  // `path` (not written here) is not worth keeping.
  auto keep_previous = [&] {
    if (file_exists(path) && checkpoint_is_complete(path)) {
      std::error_code ec;
      fs::remove(prev, ec);
      fs::create_hard_link(path, prev, ec);
      if (ec) rename_or_fail(path, prev);  // file system without hard links
    }
  };
  if (share) {
    const ShareRows r = share_rows(*share);
    write_h5_shared(
        path, *share,
        [&](const Loc& root) {
          check_consistent(path, ps);  // inside the first stage: the others wait for its end
          checkpoint_skeleton(root, ps, clock, schedule, tag, r.active_total, r.total, false);
        },
        [&](const Loc& root, hid_t dxpl) { checkpoint_rows(root, dxpl, ps, *share); },
        checkpoint_finish, keep_previous, [] {});
    return;
  }
  write_h5_atomically(
      path,
      [&](const Loc& root) {
        checkpoint_skeleton(root, ps, clock, schedule, tag, ps.n_active, ps.total(), true);
        checkpoint_finish(root);
      },
      keep_previous);
}

template <int D>
bool write_checkpoint_rows(const std::string& path, const ParticleSet<D>& ps,
                           const WriteShare& share) {
  QuietErrors quiet;
  return write_h5_shared(
      path, share, [](const Loc&) {},
      [&](const Loc& root, hid_t dxpl) { checkpoint_rows(root, dxpl, ps, share); },
      [](const Loc&) {}, [] {}, [] {});
}

namespace {

enum class ReadMode { Whole, Rows, Verify };

// A checkpoint's /schedule: names and values.
std::map<std::string, double> read_schedule(const Loc& root) {
  Handle g = open_group(root, "schedule");
  const Loc s = root.at(g.get(), "schedule");
  const auto names = read_strings(s, "names", true);
  std::vector<double> values;
  read_column(s, "values", names.size(), values);
  std::map<std::string, double> out;
  for (std::size_t i = 0; i < names.size(); ++i) out[names[i]] = values[i];
  return out;
}

// Reads a checkpoint: every row (Whole), one rank's rows (Rows: `share`), or (Verify) every
// dataset in full, one at a time and dropped once read (whole-file validation without holding
// the particle set).
template <int D>
Checkpoint<D> read_checkpoint_as(const std::string& path, ReadMode mode, const WriteShare* share) {
  QuietErrors quiet;
  Handle f = open_file(path, H5F_ACC_RDONLY);
  const Loc root{f.get(), path, "/"};
  if (!has_attr(root, "complete") || read_attr<std::int32_t>(root, "complete") != 1)
    fail(path, "", "is an incomplete checkpoint (the run stopped while writing it)");
  const int dim = read_attr<std::int32_t>(root, "dim");
  if (dim != D) {
    fail(path, "attribute 'dim'",
         "the checkpoint holds a " + std::to_string(dim) + "D run, but a " + std::to_string(D) +
             "D run was asked to restart from it");
  }
  const auto n_active = read_attr<std::uint64_t>(root, "n_active");
  const auto total = read_attr<std::uint64_t>(root, "total");
  if (n_active > total) fail(path, "attribute 'n_active'", "exceeds the particle count");
  ShareRows rows;
  std::uint64_t mine_active = 0, mine_excluded = 0;
  if (mode == ReadMode::Rows) {
    rows = share_rows(*share);
    const auto r = static_cast<std::size_t>(share->rank);
    if (rows.active_total != n_active || rows.total != total || r >= share->active.size())
      fail(path, "group '/schedule'",
           "its decomposition record (" + std::to_string(rows.active_total) + " active of " +
               std::to_string(rows.total) + ") does not match its particles (" +
               std::to_string(n_active) + " of " + std::to_string(total) + ")");
    mine_active = share->active[r];
    mine_excluded = share->excluded[r];
  }

  Checkpoint<D> c;
  if (has_attr(root, "case_identity")) {
    read_field(root, "case_identity", c.tag.identity);
    read_field(root, "case_name", c.tag.name);
    read_field(root, "case_file", c.tag.file);
  }
  auto& ps = c.particles;
  {
    Handle g = open_group(root, "particles");
    const Loc p = root.at(g.get(), "particles");
    if (H5Lexists(g.get(), "role", H5P_DEFAULT) <= 0 ||
        H5Lexists(g.get(), "rho_prev", H5P_DEFAULT) <= 0)
      fail(path, "group '/particles'",
           "was written by a Swell before 0.2 (no 'role' or 'rho_prev' dataset); restart needs a "
           "checkpoint of this version: run the case again from the start");
    ps.for_each_field([&](const FieldInfo& fi, auto& v) {
      // Optional fields are restored when the checkpoint holds them.
      if (fi.optional && H5Lexists(g.get(), fi.name, H5P_DEFAULT) <= 0) return;
      if (mode == ReadMode::Rows) {
        read_rows(p, fi.name, total, rows.active_first, mine_active, v, 0);
        read_rows(p, fi.name, total, rows.excluded_first, mine_excluded, v, mine_active);
      } else {
        read_column(p, fi.name, total, v);
      }
      if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::vector<Role>>) {
        for (Role r : v)
          if (!is_valid_role(static_cast<std::uint8_t>(r)))
            fail(path, p.dataset("role"),
                 "holds a value other than 0 (fluid), 1 (fixed wall), 2 (moving wall) or 3 "
                 "(floating)");
      }
      if (mode == ReadMode::Verify)
        std::decay_t<decltype(v)>().swap(v);  // read in full, not kept
      else if (fi.optional)
        ps.mark_enabled(fi);
    });
    ps.n_active = mode == ReadMode::Rows ? mine_active : n_active;
  }
  {
    Handle g = open_group(root, "clock");
    const Loc k = root.at(g.get(), "clock");
    clock_fields(c.clock, [&](const char* name, auto& v) { read_field(k, name, v); });
  }
  c.schedule = read_schedule(root);
  if (mode == ReadMode::Verify) c.particles = ParticleSet<D>();
  return c;
}

}  // namespace

template <int D>
Checkpoint<D> read_checkpoint(const std::string& path, const WriteShare* rows) {
  return read_checkpoint_as<D>(path, rows ? ReadMode::Rows : ReadMode::Whole, rows);
}

std::map<std::string, double> read_checkpoint_schedule(const std::string& path) {
  QuietErrors quiet;
  Handle f = open_file(path, H5F_ACC_RDONLY);
  return read_schedule(Loc{f.get(), path, "/"});
}

int checkpoint_dimension(const std::string& path) {
  QuietErrors quiet;
  Handle f = open_file(path, H5F_ACC_RDONLY);
  return read_attr<std::int32_t>(Loc{f.get(), path, "/"}, "dim");
}

std::pair<std::uint64_t, std::uint64_t> checkpoint_counts(const std::string& path) {
  QuietErrors quiet;
  Handle f = open_file(path, H5F_ACC_RDONLY);
  const Loc root{f.get(), path, "/"};
  return {read_attr<std::uint64_t>(root, "n_active"), read_attr<std::uint64_t>(root, "total")};
}

std::string latest_valid_checkpoint(const std::string& path) {
  // A full read: HDF5 keeps no checksum of the data, so a partial check could miss damage.
  // One dataset at a time: the check never holds the whole particle set.
  auto readable = [](const std::string& p, std::string& why) {
    try {
      const int dim = checkpoint_dimension(p);
      if (dim == 2) {
        read_checkpoint_as<2>(p, ReadMode::Verify, nullptr);
      } else if (dim == 3) {
        read_checkpoint_as<3>(p, ReadMode::Verify, nullptr);
      } else {
        fail(p, "attribute 'dim'", "unsupported dimension " + std::to_string(dim));
      }
      return true;
    } catch (const std::runtime_error& e) {
      why = e.what();
      return false;
    }
  };
  std::string why_path, why_prev;
  if (readable(path, why_path)) return path;
  const std::string prev = path + ".prev";
  if (readable(prev, why_prev)) return prev;
  throw std::runtime_error("no valid checkpoint to restart from: '" + path + "' (" + why_path +
                           ") and '" + prev + "' (" + why_prev + ")");
}

void hdf5_no_atexit() {
  H5dont_atexit();
}

// ---- Explicit instantiations --------------------------------------------------------------

template void Hdf5RunFile::write_snapshot<2>(long, double, const ParticleSet<2>&,
                                             const std::vector<double>&, const WriteShare*);
template void Hdf5RunFile::write_snapshot<3>(long, double, const ParticleSet<3>&,
                                             const std::vector<double>&, const WriteShare*);
template bool write_snapshot_rows<2>(const std::string&, long, const ParticleSet<2>&,
                                     const std::vector<double>&, const WriteShare&);
template bool write_snapshot_rows<3>(const std::string&, long, const ParticleSet<3>&,
                                     const std::vector<double>&, const WriteShare&);
template SnapshotData<2> read_snapshot<2>(const std::string&, const SnapshotInfo&);
template SnapshotData<3> read_snapshot<3>(const std::string&, const SnapshotInfo&);
template void write_checkpoint<2>(const std::string&, const ParticleSet<2>&, const SimulationClock&,
                                  const std::map<std::string, double>&, const CaseTag&,
                                  const WriteShare*);
template void write_checkpoint<3>(const std::string&, const ParticleSet<3>&, const SimulationClock&,
                                  const std::map<std::string, double>&, const CaseTag&,
                                  const WriteShare*);
template bool write_checkpoint_rows<2>(const std::string&, const ParticleSet<2>&,
                                       const WriteShare&);
template bool write_checkpoint_rows<3>(const std::string&, const ParticleSet<3>&,
                                       const WriteShare&);
template Checkpoint<2> read_checkpoint<2>(const std::string&, const WriteShare*);
template Checkpoint<3> read_checkpoint<3>(const std::string&, const WriteShare*);

}  // namespace swell
