// The gauges of a case: evaluated between steps at their own intervals and written as one CSV
// per gauge kind (gauges_<kind>.csv). evaluate_gauge() is shared with `swell probe`, which
// evaluates the same gauges on saved snapshots.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "case/spec.hpp"
#include "io/gauge_csv.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

// What a gauge needs to know about the run besides the particles.
struct GaugeContext {
  SolverParams params;
  int up_axis = 1;        // vertical axis (y in 2D, z in 3D)
  double floor = 0.0;     // lowest fluid level at the start (surge-front band origin)
  double line_top = 0.0;  // top of the water-height measuring line
  std::map<std::string, int> body_ids;
};

// Values of one gauge, in the order of gauge_columns(). `ace` may be empty where no force
// gauge is evaluated (post-processing).
template <int D>
std::vector<double> evaluate_gauge(const GaugeSpec& g, const GaugeContext& ctx,
                                   const ParticleSet<D>& ps, const std::vector<double>& pressure,
                                   const std::vector<Vec<D>>& ace);

// The particles the gauges may read: those inside one of `boxes` (any role) and the wall
// particles of `bodies` (force gauges). Each gauge skips every other particle by its own test
// (kernel support, measuring line, band), so evaluated on the particles in the region, kept in
// their order, a gauge gives the same value bit for bit as on the whole set. A decomposed run
// gathers only these to rank 0 for its gauges.
template <int D>
struct GaugeRegion {
  std::vector<std::pair<Vec<D>, Vec<D>>> boxes;  // lo, hi (infinite where unbounded)
  std::vector<std::uint16_t> bodies;
  bool contains(const ParticleSet<D>& ps, std::size_t i) const {
    for (const auto& [lo, hi] : boxes)
      if ((ps.pos[i].array() >= lo.array()).all() && (ps.pos[i].array() <= hi.array()).all())
        return true;
    if (is_wall(ps.role[i]))
      for (const auto b : bodies)
        if (ps.body[i] == b) return true;
    return false;
  }
};

template <int D>
GaugeRegion<D> gauge_region(const std::vector<GaugeSpec>& gauges, const GaugeContext& ctx);

template <int D>
class GaugeSet {
 public:
  // resume_after >= 0: continue the CSV files of a restarted run after that time.
  GaugeSet(const std::vector<GaugeSpec>& gauges, double default_every, GaugeContext ctx,
           const std::string& out_dir, const std::string& case_name, double resume_after);

  bool empty() const { return gauges_.empty(); }
  bool due(double time) const;
  // Samples every gauge whose time has come and writes one row per kind.
  void sample(double time, const ParticleSet<D>& ps, const std::vector<double>& pressure,
              const std::vector<Vec<D>>& ace);
  // Sensor faces (pressure gauges with a size) and height gauges with `sampling: mean` are
  // averaged over each sampling interval, runup gauges with `sampling: max` take its maximum:
  // call this after every step with the step's dt (sample() then writes the interval values).
  bool averages() const { return averaging_; }
  void accumulate(double dt, const ParticleSet<D>& ps, const std::vector<double>& pressure);
  void flush();
  void save_schedule(std::map<std::string, double>& schedule) const;
  void load_schedule(const std::map<std::string, double>& schedule);

 private:
  struct Entry {
    GaugeSpec spec;
    double every = 0.0, next = 0.0;
    int file = 0;                   // index into files_
    std::size_t first_column = 0;   // within that file's row
    double acc = 0.0, acc_t = 0.0;  // sensor face: integral of p dt and its duration so far
    std::vector<Vec<D>> points;     // sensor face: quadrature points (built on first use)
    Vec<D> normal = Vec<D>::Zero();
    double peak = 0.0;  // runup with `sampling: max`: the largest value since the last row
    bool has_peak = false;
  };
  std::vector<Entry> gauges_;
  std::vector<std::unique_ptr<GaugeCsvFile>> files_;
  std::vector<std::size_t> file_columns_;
  GaugeContext ctx_;
  std::vector<double> row_;
  std::vector<bool> present_;
  bool averaging_ = false;
  std::vector<std::uint32_t> scratch_;
};

}  // namespace swell
