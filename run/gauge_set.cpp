#include "run/gauge_set.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "solver/diagnostics.hpp"
#include "solver/gauges.hpp"
#include "solver/physics/kernels.hpp"

namespace swell {
namespace {

const char* kind_comment(GaugeSpec::Kind k) {
  switch (k) {
    case GaugeSpec::Kind::Pressure:
      return "pressure probes: Shepard-normalised kernel interpolation of fluid pressure [Pa]; "
             "empty where not sampled, nan where dry; sensor faces (size): face average of "
             "the pressure extrapolated to the wall, points above the water faded to 0, mean "
             "over the interval up to the row's time";
    case GaugeSpec::Kind::Height:
      return "water height: free-surface elevation [m] where the kernel-interpolated density "
             "along the vertical line falls below rho0/2";
    case GaugeSpec::Kind::Velocity:
      return "velocity probes: Shepard-normalised kernel interpolation of fluid velocity [m/s]";
    case GaugeSpec::Kind::Force:
      return "force and moment of the fluid on boundary bodies (2D: per metre of width)";
    case GaugeSpec::Kind::Front:
      return "surge front: largest x of fluid within the band above the floor, plus dp/2 [m]";
    case GaugeSpec::Kind::Runup:
      return "runup: elevation of the highest point of the slope line where the fluid kernel "
             "sum dp/2 off the surface (h = sqrt(dim) dp) reaches 0.3 rho0, above swl where the "
             "gauge gives one, else absolute [m]; edge: connected, the tongue attached to the "
             "sea (splashes do not count); sampling: max, the largest value since the previous "
             "row";
  }
  return "";
}

}  // namespace

// A height gauge's level (no allocation once the candidate buffer has grown).
template <int D>
double height_level(const GaugeSpec& g, const GaugeContext& ctx, const ParticleSet<D>& ps) {
  const SolverParams& p = ctx.params;
  const Vec<D> at = g.at.template head<D>();
  return with_kernel<D>(p.kernel, p.h, [&](const auto& kernel) {
    if (g.level == GaugeSpec::Level::Integral)
      return water_height_integral(ps, kernel, at, ctx.up_axis, ctx.line_top, 0.5 * p.dp, p.rho0);
    return water_height(ps, kernel, at, ctx.up_axis, ctx.line_top, 0.5 * p.dp, p.rho0);
  });
}

// A runup gauge's value (no allocation once the candidate buffer has grown). The wet criterion
// is a measurement, not the solver's smoothing: it sums with the case's kernel at h = sqrt(D) dp
// (coefh 1), the h its 0.3 rho0 threshold is set for, whatever the run's coefh. Summed at coefh
// 1.5 (h = 2.12 dp) a one-row film reads 0.35 rho0 and its edge 1.2 dp short (test_gauges).
template <int D>
double runup_level(const GaugeSpec& g, const GaugeContext& ctx, const ParticleSet<D>& ps) {
  const SolverParams& p = ctx.params;
  const double h_gauge = std::sqrt(static_cast<double>(D)) * p.dp;
  const double z = with_kernel<D>(p.kernel, h_gauge, [&](const auto& kernel) {
    return runup_elevation(ps, kernel, Vec<D>(g.from.template head<D>()),
                           Vec<D>(g.to.template head<D>()), ctx.up_axis, 0.5 * p.dp, p.dp, p.rho0,
                           0.3, g.connected);
  });
  return g.swl ? z - *g.swl : z;
}

template <int D>
std::vector<double> evaluate_gauge(const GaugeSpec& g, const GaugeContext& ctx,
                                   const ParticleSet<D>& ps, const std::vector<double>& pressure,
                                   const std::vector<Vec<D>>& ace) {
  const SolverParams& p = ctx.params;
  const Vec<D> at = g.at.template head<D>();
  return with_kernel<D>(p.kernel, p.h, [&](const auto& kernel) -> std::vector<double> {
    switch (g.kind) {
      case GaugeSpec::Kind::Pressure: {
        if (g.size) {
          const Vec<D> n = g.normal->template head<D>().normalized();
          std::vector<std::uint32_t> scratch;
          return {face_pressure(ps, pressure, kernel, face_points<D>(at, n, *g.size, p.dp), n,
                                g.offset ? *g.offset : p.h, p.rho0,
                                Vec<D>(p.gravity.template head<D>()), scratch)};
        }
        Vec<D> x = at;
        if (g.normal) x += (g.offset ? *g.offset : p.h) * Vec<D>(g.normal->template head<D>());
        return {probe_pressure(ps, pressure, kernel, x)};
      }
      case GaugeSpec::Kind::Velocity: {
        const Vec<D> v = probe_velocity(ps, kernel, at);
        return std::vector<double>(v.data(), v.data() + D);
      }
      case GaugeSpec::Kind::Height:
        return {height_level<D>(g, ctx, ps)};
      case GaugeSpec::Kind::Runup:
        return {runup_level<D>(g, ctx, ps)};
      case GaugeSpec::Kind::Front: {
        Vec<D> up = Vec<D>::Zero();
        up[ctx.up_axis] = 1.0;
        const double band = g.band ? *g.band : 2.0 * p.h;
        const double f = surge_front(ps, up, ctx.floor, band, p.dp);
        return {std::isfinite(f) ? f : std::numeric_limits<double>::quiet_NaN()};
      }
      case GaugeSpec::Kind::Force: {
        if (ace.size() < ps.size())
          throw std::invalid_argument("force gauge '" + g.name +
                                      "' needs wall accelerations, "
                                      "which only a running simulation has");
        const auto it = ctx.body_ids.find(g.body);
        if (it == ctx.body_ids.end())
          throw std::invalid_argument("force gauge '" + g.name + "': no body '" + g.body + "'");
        const Eigen::Vector3d about = g.moment_about ? *g.moment_about : Eigen::Vector3d::Zero();
        const auto load = body_load(ps, ace, it->second, about);
        std::vector<double> v(load.force.data(), load.force.data() + D);
        if constexpr (D == 2) {
          v.push_back(load.moment.z());
        } else {
          for (int d = 0; d < 3; ++d) v.push_back(load.moment[d]);
        }
        return v;
      }
    }
    return {};
  });
}

template <int D>
GaugeRegion<D> gauge_region(const std::vector<GaugeSpec>& gauges, const GaugeContext& ctx) {
  const SolverParams& p = ctx.params;
  // The kernel support plus dp: the region may hold more than a gauge reads, never less.
  const double s = kernel_support_factor(p.kernel) * p.h + p.dp;
  constexpr double inf = std::numeric_limits<double>::infinity();
  GaugeRegion<D> region;
  auto around = [&](const Vec<D>& c, double r) {
    region.boxes.emplace_back(c.array() - r, c.array() + r);
  };
  for (const auto& g : gauges) {
    const Vec<D> at = g.at.template head<D>();
    switch (g.kind) {
      case GaugeSpec::Kind::Pressure: {
        Vec<D> x = at;
        const double offset = g.offset ? *g.offset : p.h;
        if (g.normal) {  // as evaluate_gauge: a face's normal is normalised, a probe's is not
          const Vec<D> n = g.normal->template head<D>();
          x += offset * (g.size ? Vec<D>(n.normalized()) : n);
        }
        around(x, s + (g.size ? 0.5 * *g.size : 0.0));
        break;
      }
      case GaugeSpec::Kind::Velocity:
        around(at, s);
        break;
      case GaugeSpec::Kind::Height: {  // a vertical column around the line, at every height
        Vec<D> lo = at.array() - s, hi = at.array() + s;
        lo[ctx.up_axis] = -inf;
        hi[ctx.up_axis] = inf;
        region.boxes.emplace_back(lo, hi);
        break;
      }
      case GaugeSpec::Kind::Runup: {
        const Vec<D> a = g.from.template head<D>(), b = g.to.template head<D>();
        const double r = 0.5 * p.dp + 2.0 * s;  // offset + support around the line, + support
        region.boxes.emplace_back(a.cwiseMin(b).array() - r, a.cwiseMax(b).array() + r);
        break;
      }
      case GaugeSpec::Kind::Front: {  // the band above the floor, everywhere along it
        Vec<D> lo = Vec<D>::Constant(-inf), hi = Vec<D>::Constant(inf);
        lo[ctx.up_axis] = ctx.floor - p.dp;
        hi[ctx.up_axis] = ctx.floor + (g.band ? *g.band : 2.0 * p.h) + p.dp;
        region.boxes.emplace_back(lo, hi);
        break;
      }
      case GaugeSpec::Kind::Force: {
        const auto it = ctx.body_ids.find(g.body);
        if (it != ctx.body_ids.end())
          region.bodies.push_back(static_cast<std::uint16_t>(it->second));
        break;
      }
    }
  }
  return region;
}

template <int D>
GaugeSet<D>::GaugeSet(const std::vector<GaugeSpec>& gauges, double default_every, GaugeContext ctx,
                      const std::string& out_dir, const std::string& case_name, double resume_after)
    : ctx_(std::move(ctx)) {
  std::map<GaugeSpec::Kind, std::vector<std::size_t>> by_kind;
  for (std::size_t i = 0; i < gauges.size(); ++i) by_kind[gauges[i].kind].push_back(i);
  gauges_.resize(gauges.size());
  for (const auto& [kind, members] : by_kind) {
    std::vector<std::string> columns;
    const int file = static_cast<int>(files_.size());
    for (std::size_t i : members) {
      Entry& e = gauges_[i];
      e.spec = gauges[i];
      e.every = gauges[i].every > 0.0 ? gauges[i].every : default_every;
      e.next = 0.0;
      e.file = file;
      e.first_column = columns.size();
      averaging_ = averaging_ || (gauges[i].kind == GaugeSpec::Kind::Pressure && gauges[i].size) ||
                   (gauges[i].kind == GaugeSpec::Kind::Height && gauges[i].mean) ||
                   (gauges[i].kind == GaugeSpec::Kind::Runup && gauges[i].max);
      for (auto& c : gauge_columns(gauges[i], D)) columns.push_back(c);
    }
    const std::string path =
        (std::filesystem::path(out_dir) / (std::string("gauges_") + gauge_kind_name(kind) + ".csv"))
            .string();
    files_.push_back(std::make_unique<GaugeCsvFile>(
        path, std::vector<std::string>{"swell gauges, case " + case_name, kind_comment(kind)},
        columns, resume_after));
    file_columns_.push_back(columns.size());
  }
}

template <int D>
bool GaugeSet<D>::due(double time) const {
  for (const auto& e : gauges_)
    if (time >= e.next - 1e-12) return true;
  return false;
}

template <int D>
void GaugeSet<D>::sample(double time, const ParticleSet<D>& ps, const std::vector<double>& pressure,
                         const std::vector<Vec<D>>& ace) {
  for (std::size_t f = 0; f < files_.size(); ++f) {
    row_.assign(file_columns_[f], 0.0);
    present_.assign(file_columns_[f], false);
    bool any = false;
    for (auto& e : gauges_) {
      if (e.file != static_cast<int>(f) || time < e.next - 1e-12) continue;
      auto values = evaluate_gauge<D>(e.spec, ctx_, ps, pressure, ace);
      if (e.acc_t > 0.0) {  // a sensor face: the interval's mean instead of the instant's
        values[0] = e.acc / e.acc_t;
        e.acc = e.acc_t = 0.0;
      }
      if (e.has_peak) {  // a runup maximum: the interval's largest value, the row's instant
                         // included
        values[0] = std::max(values[0], e.peak);
        e.has_peak = false;
      }
      for (std::size_t k = 0; k < values.size(); ++k) {
        row_[e.first_column + k] = values[k];
        present_[e.first_column + k] = true;
      }
      if (e.spec.every_step)  // due again at the next step's time, never at this one's again:
        // past due()'s 1e-12 tolerance and a few of the time's ulps (~1.8e-12 at 1e4 s)
        e.next = time + std::max(2e-12, 4.0 * (std::nextafter(time, 2.0 * time + 1.0) - time));
      else
        while (e.next <= time + 1e-12) e.next += e.every;
      any = true;
    }
    if (any) files_[f]->write_row(time, row_, present_);
  }
}

template <int D>
void GaugeSet<D>::accumulate(double dt, const ParticleSet<D>& ps,
                             const std::vector<double>& pressure) {
  if (!averaging_ || !(dt > 0.0)) return;
  const SolverParams& p = ctx_.params;
  with_kernel<D>(p.kernel, p.h, [&](const auto& kernel) {
    for (auto& e : gauges_) {
      if (e.spec.kind == GaugeSpec::Kind::Runup && e.spec.max) {  // a runup maximum
        const double r = runup_level<D>(e.spec, ctx_, ps);
        e.peak = e.has_peak ? std::max(e.peak, r) : r;
        e.has_peak = true;
        continue;
      }
      if (e.spec.kind == GaugeSpec::Kind::Height && e.spec.mean) {  // a mean wave gauge
        e.acc += dt * height_level<D>(e.spec, ctx_, ps);
        e.acc_t += dt;
        continue;
      }
      if (e.spec.kind != GaugeSpec::Kind::Pressure || !e.spec.size) continue;
      if (e.points.empty()) {  // once: the face's quadrature points
        e.normal = e.spec.normal->template head<D>().normalized();
        e.points = face_points<D>(e.spec.at.template head<D>(), e.normal, *e.spec.size, p.dp);
      }
      e.acc += dt * face_pressure(ps, pressure, kernel, e.points, e.normal,
                                  e.spec.offset ? *e.spec.offset : p.h, p.rho0,
                                  Vec<D>(p.gravity.template head<D>()), scratch_);
      e.acc_t += dt;
    }
    return 0;
  });
}

template <int D>
void GaugeSet<D>::flush() {
  for (auto& f : files_) f->flush();
}

template <int D>
void GaugeSet<D>::save_schedule(std::map<std::string, double>& schedule) const {
  for (const auto& e : gauges_) {
    schedule["gauge." + e.spec.name] = e.next;
    if (e.acc_t > 0.0) {  // a sensor face's unfinished interval
      schedule["gauge_acc." + e.spec.name] = e.acc;
      schedule["gauge_acc_t." + e.spec.name] = e.acc_t;
    }
    if (e.has_peak) schedule["gauge_peak." + e.spec.name] = e.peak;  // a runup maximum's
  }
}

template <int D>
void GaugeSet<D>::load_schedule(const std::map<std::string, double>& schedule) {
  for (auto& e : gauges_) {
    const auto it = schedule.find("gauge." + e.spec.name);
    if (it != schedule.end()) e.next = it->second;
    const auto a = schedule.find("gauge_acc." + e.spec.name);
    const auto at = schedule.find("gauge_acc_t." + e.spec.name);
    if (a != schedule.end() && at != schedule.end()) {
      e.acc = a->second;
      e.acc_t = at->second;
    }
    const auto pk = schedule.find("gauge_peak." + e.spec.name);
    if (pk != schedule.end()) {
      e.peak = pk->second;
      e.has_peak = true;
    }
  }
}

template GaugeRegion<2> gauge_region<2>(const std::vector<GaugeSpec>&, const GaugeContext&);
template GaugeRegion<3> gauge_region<3>(const std::vector<GaugeSpec>&, const GaugeContext&);
template class GaugeSet<2>;
template class GaugeSet<3>;
template std::vector<double> evaluate_gauge<2>(const GaugeSpec&, const GaugeContext&,
                                               const ParticleSet<2>&, const std::vector<double>&,
                                               const std::vector<Vec<2>>&);
template std::vector<double> evaluate_gauge<3>(const GaugeSpec&, const GaugeContext&,
                                               const ParticleSet<3>&, const std::vector<double>&,
                                               const std::vector<Vec<3>>&);

}  // namespace swell
