// VTK output: one binary PolyData file (.vtp) per snapshot and a .pvd series file that
// ParaView opens with the simulated time attached to each snapshot.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "solver/state/particle_set.hpp"

namespace swell {

// Which particles a snapshot file holds.
enum class ParticleFilter { All, Fluid, Boundary };

// Writes the active particles (position, velocity, density, pressure, type, body, id) to
// `path` as binary VTK XML PolyData, through a temporary file renamed into place. With
// `body_names` (indexed by body), each point also gets its body's name (string array
// `body_name`) and the names are field data `body_names` (value b = the name of body b).
// A finite `time` [s] is field data `TimeValue` (one double, which ParaView shows as the
// dataset's time).
template <int D>
void write_vtp(const std::string& path, const ParticleSet<D>& ps,
               const std::vector<double>& pressure, ParticleFilter filter = ParticleFilter::All,
               const std::vector<std::string>* body_names = nullptr,
               double time = std::numeric_limits<double>::quiet_NaN());

// The name of rank `rank`'s piece of the snapshot `vtp` (".../<name>_NNNN.vtp" ->
// ".../<name>_NNNN_p<rank>.vtp") in a decomposed run.
std::string vtk_piece_name(const std::string& vtp, int rank);

// A decomposed run's snapshot: the .pvtp file at `path` that ParaView opens as one dataset made
// of the pieces `pieces` (file names relative to its folder), each written by write_vtp on its
// rank; `normals` and `body_names` say whether write_vtp wrote those arrays. Written through a
// temporary file renamed into place.
void write_pvtp(const std::string& path, const std::vector<std::string>& pieces, bool normals,
                bool body_names);

// A .pvd collection, rewritten (atomically) each time a snapshot is added.
class PvdSeries {
 public:
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  // `file` is relative to the .pvd's folder.
  void add(double time, const std::string& file);
  // Reloads the entries of an existing series up to time t_keep (restart); later ones and
  // their files are dropped from the series.
  void resume(double t_keep);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

// Writes `text` to `path` through `path.tmp` and a rename, so readers never see half a file.
void write_file_atomically(const std::string& path, const std::string& text);

// Bad input, found before any work: throws std::invalid_argument naming `option` when the folder
// `path` would be written into does not exist (a bare file name writes into the current folder).
void require_output_folder(const std::string& path, const std::string& option);

}  // namespace swell
