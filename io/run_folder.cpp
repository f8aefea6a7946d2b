#include "io/run_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace swell {
namespace {

namespace fs = std::filesystem;

bool ends_with_any(std::string_view s, std::initializer_list<std::string_view> tails) {
  return std::any_of(tails.begin(), tails.end(),
                     [&](std::string_view t) { return s.ends_with(t); });
}

bool is_top_level_run_file(std::string_view f) {
  if (f == "diagnostics.csv" || f == "run_summary.txt" || f == "diagnostics.csv.tmp" ||
      f == "run.log" || f == "run_info.yaml" || f == "run_info.yaml.tmp")
    return true;
  if (f.starts_with("gauges_") && ends_with_any(f, {".csv", ".csv.tmp"})) return true;
  return ends_with_any(f, {".h5", ".h5.tmp", ".h5.prev", ".h5.corrupt", ".pvd", ".pvd.tmp"});
}

// The number NNNN of vtk/<name>_NNNN.vtp, <name>_fluid_NNNN.vtp or <name>_boundary_NNNN.vtp,
// and of a decomposed run's <name>..._NNNN.pvtp and its pieces <name>..._NNNN_p<rank>.vtp;
// -1 for any other file name.
long vtk_index(std::string_view f, const std::string& name) {
  if (f.ends_with(".pvtp")) {
    f.remove_suffix(5);
  } else if (f.ends_with(".vtp")) {
    f.remove_suffix(4);
    const auto p = f.rfind("_p");
    if (p != std::string_view::npos && p + 2 < f.size() &&
        f.substr(p + 2).find_first_not_of("0123456789") == std::string_view::npos)
      f = f.substr(0, p);  // a piece
  } else {
    return -1;
  }
  for (std::string_view head :
       {std::string_view("_fluid_"), std::string_view("_boundary_"), std::string_view("_")}) {
    const std::string prefix = name + std::string(head);
    if (!f.starts_with(prefix)) continue;
    const std::string_view digits = f.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string_view::npos)
      continue;
    return std::stol(std::string(digits));
  }
  return -1;
}

}  // namespace

OutputLock::OutputLock(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  for (fs::path p = fs::absolute(dir_, ec); !ec && !p.empty() && !fs::exists(p, ec);
       p = p.parent_path()) {
    created_root_ = p;
    if (p == p.parent_path()) break;
  }
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create the output folder " + dir + ": " + ec.message());
  const std::string path = (fs::path(dir) / ".swell.lock").string();
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw std::runtime_error("cannot create the lock file " + path + ": " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char buf[32] = {};
    const ssize_t n = ::pread(fd_, buf, sizeof buf - 1, 0);
    ::close(fd_);
    fd_ = -1;
    if (err != EWOULDBLOCK)
      throw std::runtime_error("cannot lock " + path + ": " + std::strerror(err));
    const std::string pid = n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "unknown";
    throw std::invalid_argument(
        "output folder " + dir + " is in use by another swell run (pid " +
        pid.substr(0, pid.find_first_not_of("0123456789")) + ", lock " + path +
        "): wait for it to end or stop it, or choose another folder with -o");
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // The pid is only for messages; the lock itself holds.
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  std::error_code ec;
  bool only_lock = !created_root_.empty();
  if (only_lock) {
    for (const auto& e : fs::directory_iterator(dir_, ec))
      if (e.path().filename() != ".swell.lock") only_lock = false;
    only_lock = only_lock && !ec;
  }
  if (only_lock) fs::remove(dir_ / ".swell.lock", ec);  // before the flock goes: no new holder
  ::close(fd_);                                         // releases the flock
  if (!only_lock || ec) return;
  // The folders created for this run, now empty, innermost first (remove() keeps non-empty
  // ones, e.g. one another process has just started to use).
  for (fs::path p = fs::absolute(dir_, ec); !ec && !p.empty(); p = p.parent_path()) {
    if (!fs::remove(p, ec) || p == created_root_) break;
  }
}

std::vector<std::string> run_files(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string f = e.path().filename().string();
    if (e.is_regular_file(ec) && is_top_level_run_file(f)) out.push_back(f);
  }
  // Snapshot folders: VTK files and HDF5 snapshot files (and their temporaries).
  const auto scan = [&](const char* sub, std::string_view ext) {
    const fs::path d = fs::path(dir) / sub;
    if (!fs::is_directory(d, ec)) return;
    const std::string tmp = std::string(ext) + ".tmp";
    for (const auto& e : fs::directory_iterator(d, ec)) {
      const std::string f = e.path().filename().string();
      if (e.is_regular_file(ec) && (f.ends_with(ext) || f.ends_with(tmp)))
        out.push_back(std::string(sub) + "/" + f);
    }
  };
  scan("vtk", ".vtp");
  scan("vtk", ".pvtp");
  scan("snapshots", ".h5");
  std::sort(out.begin(), out.end());
  return out;
}

void remove_run_files(const std::string& dir) {
  for (const auto& f : run_files(dir)) {
    std::error_code ec;
    fs::remove(fs::path(dir) / f, ec);
    if (ec)
      throw std::runtime_error("cannot remove " + (fs::path(dir) / f).string() +
                               " of the earlier run: " + ec.message());
  }
}

void remove_vtk_snapshots_from(const std::string& dir, const std::string& name, int first) {
  const fs::path d = fs::path(dir) / "vtk";
  std::error_code ec;
  if (!fs::is_directory(d, ec)) return;
  std::vector<fs::path> stale;
  for (const auto& e : fs::directory_iterator(d, ec)) {
    const std::string f = e.path().filename().string();
    if (vtk_index(f, name) >= first || f.ends_with(".vtp.tmp") || f.ends_with(".pvtp.tmp"))
      stale.push_back(e.path());
  }
  for (const auto& p : stale) {
    fs::remove(p, ec);
    if (ec)
      throw std::runtime_error("cannot remove the stale snapshot " + p.string() + ": " +
                               ec.message());
  }
}

}  // namespace swell
