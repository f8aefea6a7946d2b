// The pieces of a run's outputs that are not a file format of their own: the gauges' view of
// the run, the diagnostics row, snapshot file names, the shared snapshot of a decomposed run,
// the metadata of the HDF5 run file and the ETA's format.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "case/setup.hpp"
#include "case/spec.hpp"
#include "io/hdf5_file.hpp"
#include "io/provenance.hpp"
#include "io/vtk_writer.hpp"
#include "parallel/comm.hpp"
#include "run/gauge_set.hpp"
#include "run/run.hpp"
#include "solver/diagnostics.hpp"

namespace swell {

// A duration for the progress line: m:ss or h:mm:ss; "--:--" when unknown.
std::string format_duration(double s);

// What the gauges know of the run besides the particles (every rank builds the same).
template <int D>
inline GaugeContext gauge_context(const CaseSetup<D>& setup) {
  GaugeContext c;
  c.params = setup.params;
  c.up_axis = D - 1;
  c.floor = setup.floor;
  c.line_top = setup.params.domain_max[D - 1];
  for (std::size_t b = 0; b < setup.bodies.size(); ++b)
    c.body_ids[setup.bodies[b].name] = static_cast<int>(b);
  return c;
}

// The diagnostics row (steps, dt, fluid count, mass, kinetic energy, max speed, front) over
// every rank: each its own particles, combined by `red` (collective).
template <int D, class Reduce>
std::vector<double> diagnostics_row(const ParticleSet<D>& local, const Reduce& red, long steps,
                                    double dt, const Vec<D>& up, double floor, double band,
                                    double dp) {
  const auto tot = fluid_totals(local);
  const double count = red.sum(static_cast<double>(tot.count));
  const double mass = red.sum(tot.mass), ke = red.sum(tot.kinetic_energy);
  const double vmax = red.max(tot.max_speed);
  const double front = red.max(surge_front(local, up, floor, band, dp));
  return {double(steps), dt, count, mass, ke, vmax, front};
}

// The VTK files of snapshot `k` (relative to the output folder): vtk/<name>[_part]_NNNN.vtp,
// or .pvtp on several ranks with shared output (pieces: vtk_piece_name).
std::string vtk_file(const std::string& name, const char* part, int k, bool pieces);

// The collective part of a snapshot of a decomposed run with shared output: every rank writes
// its VTK pieces and its rows of the HDF5 snapshot; rank 0 (h5/pvd given) also the .pvtp files,
// the .pvd entries and the HDF5 run file's index. `normals`: the pieces hold wall normals (mDBC).
// Every rank ends at the same agreement: on any rank's failure rank 0 throws, the others return
// false.
template <int D>
bool shared_snapshot(const std::filesystem::path& out, const CaseSpec& spec, int k, long step,
                     double time, const ParticleSet<D>& ps, const std::vector<double>& p,
                     const std::vector<std::string>& body_names, bool normals,
                     const WriteShare& share, const parallel::Comm& comm, Hdf5RunFile* h5,
                     std::vector<PvdSeries*> pvds);

// The HDF5 run file's metadata: the case, its resolution and particles, how the run was made.
template <int D>
RunMetadata make_metadata(const CaseSpec& spec, const CaseSetup<D>& setup, const RunSummary& sum,
                          const Provenance& prov);

}  // namespace swell
