// The output folder of `swell run`: a lock held for the run's life, the files an earlier run
// left there, and their removal (`--overwrite`).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace swell {

// An exclusive flock on DIR/.swell.lock (created with DIR if needed), released when the
// object dies or the process ends, however it ends. Throws std::invalid_argument naming the
// folder and the holder's pid if another process holds it. A folder the lock created and
// that holds nothing but the lock when the object dies (a run refused before it wrote
// anything) is removed again, with the parents it created.
class OutputLock {
 public:
  explicit OutputLock(const std::string& dir);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  int fd_ = -1;
  std::filesystem::path dir_, created_root_;  // the topmost folder this lock created, if any
};

// The files in DIR that a `swell run` writes (relative names, sorted): checkpoint.h5*, run
// files (*.h5) and their temporaries, *.pvd, gauges_*.csv, diagnostics.csv, run_summary.txt,
// run_info.yaml,
// vtk/*.vtp and snapshots/*.h5. Other files are not a run's and are never touched.
std::vector<std::string> run_files(const std::string& dir);

// Removes every file run_files() lists (not the lock).
void remove_run_files(const std::string& dir);

// Removes the VTK snapshots vtk/<name>_NNNN.vtp (and _fluid_/_boundary_ ones) numbered
// `first` or above: a restart rewrites the series from there.
void remove_vtk_snapshots_from(const std::string& dir, const std::string& name, int first);

}  // namespace swell
