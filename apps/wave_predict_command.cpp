#include "apps/wave_predict_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "io/provenance.hpp"
#include "io/vtk_writer.hpp"
#include "validation/gauge_column.hpp"
#include "waves/analysis.hpp"
#include "waves/record.hpp"

namespace swell {

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<double> numbers(const std::string& s, const char* option) {
  std::vector<double> out;
  for (const std::string& item : split(s)) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !std::isfinite(v))
      throw std::invalid_argument(std::string(option) + ": expected numbers x1,x2,..., got '" +
                                  item + "'");
    out.push_back(v);
  }
  if (out.empty()) throw std::invalid_argument(std::string(option) + ": no numbers given");
  return out;
}

// Linear interpolation of (t, v) at time s (held at the ends).
double at_time(const std::vector<double>& t, const std::vector<double>& v, double s) {
  if (s <= t.front()) return v.front();
  if (s >= t.back()) return v.back();
  const auto i = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), s) - t.begin());
  const double w = (s - t[i - 1]) / (t[i] - t[i - 1]);
  return v[i - 1] + w * (v[i] - v[i - 1]);
}

}  // namespace

void run_waves_predict(const WavesPredictOptions& opt, std::ostream& out) {
  if (!opt.csv.empty()) require_output_folder(opt.csv, "--csv");
  if (!(opt.depth > 0.0)) throw std::invalid_argument("--depth: a depth > 0 m is required");
  const waves::GaugeColumn record = waves::read_gauge_column(opt.file, opt.paddle);
  const std::vector<double> at = numbers(opt.at, "--at");
  for (double x : at)
    if (!(x >= 0.0)) throw std::invalid_argument("--at: distances must be >= 0 m");
  const std::vector<std::string> probes = split(opt.compare);
  if (!probes.empty() && probes.size() != at.size())
    throw std::invalid_argument("--compare: one probe column per --at distance (" +
                                std::to_string(at.size()) + "), got " +
                                std::to_string(probes.size()));
  waves::PaddleGeometry paddle;
  paddle.depth = opt.depth;
  if (std::isfinite(opt.hinge)) {
    paddle.type = waves::PaddleGeometry::Type::Flap;
    paddle.hinge_height = opt.hinge;
  }
  // A uniform time base at the record's median step (a measured record usually is uniform).
  const std::vector<double>& t = record.t;
  std::vector<double> steps;
  for (std::size_t i = 1; i < t.size(); ++i) steps.push_back(t[i] - t[i - 1]);
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const double dt = steps[steps.size() / 2];
  const auto n = static_cast<std::size_t>(std::floor((t.back() - t.front()) / dt)) + 1;
  std::vector<double> time(n), x(n);
  for (std::size_t i = 0; i < n; ++i) {
    time[i] = t.front() + static_cast<double>(i) * dt;
    x[i] = at_time(t, record.eta, time[i]);
  }
  const double t0 = std::isfinite(opt.from) ? opt.from : time.front();
  const double t1 = std::isfinite(opt.to) ? opt.to : time.back();
  if (!probes.empty() && !(t1 > t0))
    throw std::invalid_argument("--from/--to: the window must have --to > --from");

  std::ostringstream rep;
  rep.precision(4);
  rep << "paddle record " << opt.file << " column " << record.name << ": " << t.size() << " rows, "
      << time.front() << " .. " << time.back() << " s, dt " << dt << " s; "
      << (paddle.type == waves::PaddleGeometry::Type::Flap ? "flap" : "piston") << ", depth "
      << opt.depth << " m\n"
      << "linear theory (Biesel transfer function, no evanescent modes)\n";
  std::vector<std::vector<double>> predicted, measured;
  for (std::size_t p = 0; p < at.size(); ++p) {
    predicted.push_back(
        waves::propagate_paddle_record(x, dt, paddle, at[p], opt.gravity, opt.fmax));
    if (probes.empty()) continue;
    const waves::GaugeColumn probe = waves::read_gauge_column(opt.file, probes[p]);
    std::vector<double> m(n);
    for (std::size_t i = 0; i < n; ++i) m[i] = at_time(probe.t, probe.eta, time[i]);
    measured.push_back(m);
    // Window statistics; the phase lag maximises the cross-correlation over +-2 s (refined by a
    // parabola through the best three lags).
    const auto window = [&](std::size_t i) { return time[i] >= t0 && time[i] <= t1; };
    double se = 0.0, sm = 0.0, crest_m = -1e300, crest_p = -1e300;
    std::size_t count = 0;
    const std::vector<double>& q = predicted.back();
    for (std::size_t i = 0; i < n; ++i) {
      if (!window(i)) continue;
      se += (q[i] - m[i]) * (q[i] - m[i]);
      sm += m[i] * m[i];
      crest_m = std::max(crest_m, m[i]);
      crest_p = std::max(crest_p, q[i]);
      ++count;
    }
    if (count < 4) throw std::invalid_argument("--from/--to: fewer than 4 samples in the window");
    const long max_lag = static_cast<long>(std::lround(2.0 / dt));
    std::vector<double> corr;
    for (long lag = -max_lag; lag <= max_lag; ++lag) {
      double c = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const long j = static_cast<long>(i) + lag;
        if (!window(i) || j < 0 || j >= static_cast<long>(n)) continue;
        c += m[i] * q[static_cast<std::size_t>(j)];
      }
      corr.push_back(c);
    }
    const auto best = static_cast<long>(std::max_element(corr.begin(), corr.end()) - corr.begin());
    double lag = static_cast<double>(best - max_lag);
    if (best > 0 && best + 1 < static_cast<long>(corr.size())) {
      const double a = corr[best - 1], b = corr[best], c = corr[best + 1];
      const double den = a - 2 * b + c;
      if (den < 0.0) lag += 0.5 * (a - c) / den;
    }
    const double rms_m = std::sqrt(sm / count), rms_e = std::sqrt(se / count);
    rep << "  x = " << at[p] << " m, probe " << probe.name << ", window " << t0 << " .. " << t1
        << " s:\n"
        << "    RMS: measured " << rms_m << " m, predicted - measured " << rms_e << " m ("
        << 100.0 * rms_e / rms_m << " % of the measured RMS)\n"
        << "    highest crest: measured " << crest_m << " m, predicted " << crest_p << " m ("
        << 100.0 * (crest_p / crest_m - 1.0) << " %)\n"
        << "    phase: the prediction lags the probe by " << lag * dt
        << " s (cross-correlation peak)\n";
  }
  if (!opt.csv.empty()) {
    std::ostringstream csv;
    csv.precision(9);
    csv << "# swell waves predict: linear theory from " << opt.file << " column " << record.name
        << ", depth " << opt.depth << " m\n"
        << provenance_text(capture_provenance(), "# ") << "time [s]";
    for (std::size_t p = 0; p < at.size(); ++p) {
      csv << ",eta_" << at[p] << " [m]";
      if (!probes.empty()) csv << "," << probes[p] << " [m]";
    }
    csv << "\n";
    for (std::size_t i = 0; i < n; ++i) {
      csv << time[i];
      for (std::size_t p = 0; p < at.size(); ++p) {
        csv << "," << predicted[p][i];
        if (!probes.empty()) csv << "," << measured[p][i];
      }
      csv << "\n";
    }
    write_file_atomically(opt.csv, csv.str());
    rep << "prediction written to " << opt.csv << "\n";
  }
  out << rep.str();
}

Subcommand add_waves_predict_command(CLI::App& waves) {
  auto opt = std::make_shared<WavesPredictOptions>();
  auto* a = waves.add_subcommand(
      "predict", "linear-theory surface elevation from a measured paddle record (and probes)");
  a->add_option("file", opt->file, "CSV: time column first, then paddle and probe columns")
      ->required();
  a->add_option("--paddle", opt->paddle, "paddle displacement column [m]")->required();
  a->add_option("--at", opt->at, "distances from the paddle x1,x2,... [m]")->required();
  a->add_option("--depth", opt->depth, "still-water depth at the paddle [m]")->required();
  a->add_option("--compare", opt->compare, "probe columns P1,P2,..., one per distance");
  a->add_option("--hinge", opt->hinge, "a flap hinged this height above the bed [m]");
  a->add_option("--from", opt->from, "comparison window start [s]");
  a->add_option("--to", opt->to, "comparison window end [s]");
  a->add_option("--fmax", opt->fmax, "drop components above this frequency [Hz]");
  a->add_option("--gravity", opt->gravity, "g [m/s^2] (default 9.81)");
  a->add_option("--csv", opt->csv, "write the prediction (and probes) to this CSV file");
  return Subcommand(a, [opt] {
    run_waves_predict(*opt, std::cout);
    return 0;
  });
}

}  // namespace swell
