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

template <int D>
void Hdf5RunFile::write_snapshot(long step, double time, const ParticleSet<D>& ps,
                                 const std::vector<double>& pressure) {
  QuietErrors quiet;
  const std::size_t n = ps.size();
  const std::string name = snapshot_name(step);
  const std::string file = (fs::path(path_).parent_path() / snapshot_file(step)).string();
  if (pressure.size() < n) {
    fail(file, "group '/particles/" + name + "'",
         "pressure has " + std::to_string(pressure.size()) + " values for " + std::to_string(n) +
             " active particles");
  }
  ++writes_;
  write_h5_atomically(
      file,
      [&](const Loc& root) {
        write_metadata(root, meta_);
        Handle pg = create_group(root, "particles");
        const Loc particles = root.at(pg.get(), "particles");
        Handle g = create_group(particles, name);
        const Loc snap = particles.at(g.get(), name);
        // The fields of the table that have a snapshot name, plus the pressure.
        ps.for_each_field([&](const FieldInfo& f, const auto& a) {
          if (!f.snapshot || !ps.enabled(f)) return;
          write_column(snap, f.snapshot, a, n, true);
          write_units(snap, f.snapshot, snapshot_units(f.snapshot, D));
        });
        write_column(snap, "p", pressure, n, true);
        write_units(snap, "p", snapshot_units("p", D));
        // Attributes last: a group without them was cut short and is skipped by readers.
        write_attr(snap, "time", time);
        write_attr<std::int64_t>(snap, "step", step);
      },
      [&] {
        if (kill_point_ == 1 && writes_ == kill_at_) std::raise(SIGKILL);
      });
  auto it = std::find_if(entries_.begin(), entries_.end(),
                         [&](const Entry& e) { return e.step >= step; });
  if (it != entries_.end() && it->step == step)
    it->time = time;
  else
    entries_.insert(it, {step, time});
  write_index();
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

template <int D>
void write_checkpoint(const std::string& path, const ParticleSet<D>& ps,
                      const SimulationClock& clock, const std::map<std::string, double>& schedule,
                      const CaseTag& tag) {
  QuietErrors quiet;
  const std::size_t total = ps.total();
  bool consistent = ps.n_active <= total;
  checkpoint_arrays(ps, [&](const char*, const auto& v) { consistent &= v.size() == total; });
  if (!consistent) fail(path, "", "cannot save a particle set whose arrays differ in size");

  const std::string prev = path + ".prev";
  write_h5_atomically(
      path,
      [&](const Loc& root) {
        write_attr<std::int32_t>(root, "dim", D);
        write_attr<std::uint64_t>(root, "n_active", ps.n_active);
        write_attr<std::uint64_t>(root, "total", total);
        write_field(root, "case_identity", tag.identity);
        write_field(root, "case_name", tag.name);
        write_field(root, "case_file", tag.file);
        {
          Handle g = create_group(root, "particles");
          const Loc p = root.at(g.get(), "particles");
          checkpoint_arrays(
              ps, [&](const char* name, const auto& v) { write_column(p, name, v, total, false); });
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
        // Last: a file without this mark was cut short and is never restarted from.
        write_attr<std::int32_t>(root, "complete", 1);
      },
      [&] {
        // Keep the previous checkpoint as .prev through a hard link, so `path` names a
        // complete checkpoint at every moment; the rename then replaces it atomically. An
        // incomplete file at `path` (not written here) is not worth keeping.
        if (file_exists(path) && checkpoint_is_complete(path)) {
          std::error_code ec;
          fs::remove(prev, ec);
          fs::create_hard_link(path, prev, ec);
          if (ec) rename_or_fail(path, prev);  // file system without hard links
        }
      });
}

template <int D>
Checkpoint<D> read_checkpoint(const std::string& path) {
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
      read_column(p, fi.name, total, v);
      if (fi.optional) ps.mark_enabled(fi);
    });
    for (Role r : ps.role) {
      if (!is_valid_role(static_cast<std::uint8_t>(r)))
        fail(path, p.dataset("role"),
             "holds a value other than 0 (fluid), 1 (fixed wall), 2 (moving wall) or 3 (floating)");
    }
    ps.n_active = n_active;
  }
  {
    Handle g = open_group(root, "clock");
    const Loc k = root.at(g.get(), "clock");
    clock_fields(c.clock, [&](const char* name, auto& v) { read_field(k, name, v); });
  }
  {
    Handle g = open_group(root, "schedule");
    const Loc s = root.at(g.get(), "schedule");
    const auto names = read_strings(s, "names", true);
    std::vector<double> values;
    read_column(s, "values", names.size(), values);
    for (std::size_t i = 0; i < names.size(); ++i) c.schedule[names[i]] = values[i];
  }
  return c;
}

int checkpoint_dimension(const std::string& path) {
  QuietErrors quiet;
  Handle f = open_file(path, H5F_ACC_RDONLY);
  return read_attr<std::int32_t>(Loc{f.get(), path, "/"}, "dim");
}

std::string latest_valid_checkpoint(const std::string& path) {
  // A full read: HDF5 keeps no checksum of the data, so a partial check could miss damage.
  auto readable = [](const std::string& p, std::string& why) {
    try {
      const int dim = checkpoint_dimension(p);
      if (dim == 2) {
        read_checkpoint<2>(p);
      } else if (dim == 3) {
        read_checkpoint<3>(p);
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
                                             const std::vector<double>&);
template void Hdf5RunFile::write_snapshot<3>(long, double, const ParticleSet<3>&,
                                             const std::vector<double>&);
template SnapshotData<2> read_snapshot<2>(const std::string&, const SnapshotInfo&);
template SnapshotData<3> read_snapshot<3>(const std::string&, const SnapshotInfo&);
template void write_checkpoint<2>(const std::string&, const ParticleSet<2>&, const SimulationClock&,
                                  const std::map<std::string, double>&, const CaseTag&);
template void write_checkpoint<3>(const std::string&, const ParticleSet<3>&, const SimulationClock&,
                                  const std::map<std::string, double>&, const CaseTag&);
template Checkpoint<2> read_checkpoint<2>(const std::string&);
template Checkpoint<3> read_checkpoint<3>(const std::string&);

}  // namespace swell
