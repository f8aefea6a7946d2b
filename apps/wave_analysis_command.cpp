#include "apps/wave_analysis_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "io/provenance.hpp"
#include "io/vtk_writer.hpp"
#include "validation/gauge_column.hpp"
#include "waves/analysis.hpp"

namespace swell {
namespace {

namespace wv = swell::waves;

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto b = item.find_first_not_of(' ');
    const auto e = item.find_last_not_of(' ');
    items.push_back(b == std::string::npos ? "" : item.substr(b, e - b + 1));
  }
  return items;
}

std::array<double, 3> three_numbers(const std::string& text, const std::string& option) {
  const auto items = split_list(text);
  std::array<double, 3> v{};
  if (items.size() != 3)
    throw std::invalid_argument(option + ": expected three numbers x1,x2,x3, got '" + text + "'");
  for (int i = 0; i < 3; ++i) {
    char* end = nullptr;
    v[i] = std::strtod(items[i].c_str(), &end);
    if (items[i].empty() || *end != '\0' || !std::isfinite(v[i]))
      throw std::invalid_argument(option + ": '" + items[i] + "' is not a number");
  }
  return v;
}

void require_positive(double v, const std::string& option) {
  if (!std::isnan(v) && !(v > 0.0 && std::isfinite(v)))
    throw std::invalid_argument(option + ": expected a number > 0, got " + fmt(v));
}

// A column cut to the window.
struct Record {
  wv::GaugeColumn column;
  std::vector<double> t, eta;
};

Record load(const std::string& file, const std::string& name, Window w) {
  Record r;
  r.column = wv::read_gauge_column(file, name);
  for (std::size_t i = 0; i < r.column.t.size(); ++i)
    if (w.contains(r.column.t[i])) {
      r.t.push_back(r.column.t[i]);
      r.eta.push_back(r.column.eta[i]);
    }
  if (r.t.size() < 8)
    throw std::invalid_argument(file + ": gauge '" + r.column.name + "' has " +
                                std::to_string(r.t.size()) +
                                " samples in the window t = " + fmt(w.t0) + " to " + fmt(w.t1) +
                                " s (its record: " + fmt(r.column.t.front()) + " to " +
                                fmt(r.column.t.back()) + " s); at least 8 needed");
  return r;
}

bool uniform(const std::vector<double>& t) {
  try {
    wv::check_uniform(t);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

// One uniform time base for the records the spectra use: their own times when they share
// them and those are uniform, else linear interpolation onto the common time range at the
// first record's mean spacing.
struct TimeBase {
  std::vector<double> t;
  std::vector<std::vector<double>> eta;
  bool resampled = false;
  double max_deviation = 0.0;  // of the input spacing from the mean, relative
};

TimeBase time_base(const std::vector<const Record*>& records) {
  TimeBase b;
  bool same = true;
  for (const auto* r : records) same = same && r->t == records.front()->t;
  const auto& t0 = records.front()->t;
  const double dt = (t0.back() - t0.front()) / static_cast<double>(t0.size() - 1);
  for (const auto* r : records)
    for (std::size_t i = 0; i + 1 < r->t.size(); ++i)
      b.max_deviation = std::max(b.max_deviation, std::abs(r->t[i + 1] - r->t[i] - dt) / dt);
  if (same && uniform(t0)) {
    b.t = t0;
    for (const auto* r : records) b.eta.push_back(r->eta);
    return b;
  }
  b.resampled = true;
  double start = t0.front(), end = t0.back();
  for (const auto* r : records) {
    start = std::max(start, r->t.front());
    end = std::min(end, r->t.back());
  }
  if (!(end > start)) throw std::invalid_argument("the gauges' records do not overlap in time");
  const auto n = static_cast<std::size_t>(std::floor((end - start) / dt + 1e-9)) + 1;
  for (std::size_t i = 0; i < n; ++i)
    b.t.push_back(std::min(start + static_cast<double>(i) * dt, end));
  for (const auto* r : records) b.eta.push_back(wv::interpolate_linear(r->t, r->eta, b.t));
  return b;
}

std::string unit_of(const Record& r) {
  return r.column.unit.empty() ? "" : " " + r.column.unit;
}

void print_parameters(std::ostream& out, const wv::SpectralParameters& p, const std::string& u) {
  out << "  Hm0 = " << fmt(p.hm0) << u << ", Tp = " << fmt(p.tp) << " s (fp = " << fmt(p.fp)
      << " Hz), Tm01 = " << fmt(p.tm01) << " s, Tm02 = " << fmt(p.tm02) << " s\n";
}

std::string band_text(const wv::Band& band) {
  return fmt(band.fmin) + " to " + (std::isfinite(band.fmax) ? fmt(band.fmax) : "inf") + " Hz";
}

}  // namespace

void run_waves_analyse(const WavesAnalyseOptions& opt, std::ostream& out) {
  if (!opt.csv.empty()) require_output_folder(opt.csv, "--csv");
  if (opt.gauge.empty() && opt.reflection.empty())
    throw std::invalid_argument("waves analyse: give --gauge NAME and/or --reflection G1,G2,G3");
  require_positive(opt.period, "--period");
  require_positive(opt.segment, "--segment");
  require_positive(opt.depth, "--depth");
  require_positive(opt.gravity, "--gravity");
  if (opt.harmonics < 1 || opt.harmonics > 100)
    throw std::invalid_argument("--harmonics: expected 1 to 100, got " +
                                std::to_string(opt.harmonics));
  if (opt.crossing != "up" && opt.crossing != "down")
    throw std::invalid_argument("--crossing: expected up or down, got '" + opt.crossing + "'");
  Window w;
  if (!std::isnan(opt.from)) w.t0 = opt.from;
  if (!std::isnan(opt.to)) w.t1 = opt.to;
  if (!(w.t1 > w.t0))
    throw std::invalid_argument("--from " + fmt(w.t0) + " --to " + fmt(w.t1) +
                                ": the window is empty");
  wv::Band band;
  if (!std::isnan(opt.fmin)) band.fmin = opt.fmin;
  if (!std::isnan(opt.fmax)) band.fmax = opt.fmax;
  if (!(band.fmin >= 0.0) || !(band.fmax > band.fmin))
    throw std::invalid_argument("--fmin " + fmt(band.fmin) + " --fmax " + fmt(band.fmax) +
                                ": expected 0 <= fmin < fmax");
  wv::SpectrumOptions sopt;
  if (!std::isnan(opt.segment)) sopt.segment_seconds = opt.segment;

  // Read everything first, so a bad column is reported before any output.
  std::vector<Record> records;
  if (!opt.gauge.empty()) records.push_back(load(opt.file, opt.gauge, w));
  std::array<double, 3> x{};
  if (!opt.reflection.empty()) {
    const auto names = split_list(opt.reflection);
    if (names.size() != 3 ||
        std::any_of(names.begin(), names.end(), [](const std::string& s) { return s.empty(); }))
      throw std::invalid_argument("--reflection: expected three gauge names G1,G2,G3, got '" +
                                  opt.reflection + "'");
    if (opt.positions.empty() || std::isnan(opt.depth))
      throw std::invalid_argument("--reflection needs --positions x1,x2,x3 and --depth d");
    x = three_numbers(opt.positions, "--positions");
    if (!(x[0] < x[1] && x[1] < x[2]))
      throw std::invalid_argument(
          "--positions: expected x1 < x2 < x3 (incident waves travel "
          "towards +x), got " +
          opt.positions);
    for (const auto& n : names) records.push_back(load(opt.file, n, w));
  }
  std::vector<const Record*> used;
  for (const auto& r : records) used.push_back(&r);
  const TimeBase base = time_base(used);
  const double dt = (base.t.back() - base.t.front()) / static_cast<double>(base.t.size() - 1);

  // The report is printed once everything has been computed, so an error prints nothing else.
  std::ostringstream rep;
  rep << "wave analysis of " << opt.file << "\n";
  rep << "  window: t = " << fmt(base.t.front()) << " to " << fmt(base.t.back()) << " s, "
      << base.t.size() << " samples, dt = " << fmt(dt) << " s";
  if (base.resampled)
    rep << " (resampled linearly for the spectra: the input spacing varies by up to "
        << fmt(100.0 * base.max_deviation) << " %)";
  rep << "\n";

  wv::Spectrum spectrum;
  if (!opt.gauge.empty()) {
    const Record& g = records.front();
    const std::string u = unit_of(g);
    rep << "gauge " << g.column.name << (g.column.unit.empty() ? "" : " [" + g.column.unit + "]")
        << "\n";
    const auto kind = opt.crossing == "up" ? wv::Crossing::Up : wv::Crossing::Down;
    const auto zc = wv::zero_crossing(g.t, g.eta, kind);
    rep << "zero crossing (" << opt.crossing << "-crossing; mean level " << fmt(zc.mean_level) << u
        << " removed): " << zc.count << " waves\n";
    if (zc.count > 0) {
      rep << "  H_mean = " << fmt(zc.h_mean) << u << ", H_1/3 = " << fmt(zc.h_third) << u
          << ", H_max = " << fmt(zc.h_max) << u << "\n";
      rep << "  T_mean = " << fmt(zc.t_mean) << " s, T_1/3 = " << fmt(zc.t_third) << " s\n";
    }
    if (!std::isnan(opt.period)) {
      const auto fit = wv::fit_harmonics(g.t, g.eta, 1.0 / opt.period, opt.harmonics);
      rep << "harmonics (least squares, T = " << fmt(opt.period) << " s, " << fit.samples
          << " samples; eta = a0 + sum a_n cos(n w t - phi_n)): a0 = " << fmt(fit.mean) << u
          << ", rms residual " << fmt(fit.rms_residual) << u << "\n";
      for (const auto& h : fit.harmonics)
        rep << "  n = " << h.n << ": f = " << fmt(h.frequency) << " Hz, a = " << fmt(h.amplitude)
            << u << ", phi = " << fmt(h.phase) << " rad\n";
      if (!std::isnan(opt.depth) && fit.harmonics.size() >= 2) {
        const auto sp =
            wv::split_second_harmonic(fit.harmonics[0], fit.harmonics[1], opt.depth, opt.gravity);
        rep << "  second harmonic in depth " << fmt(opt.depth)
            << " m: bound (Stokes, from a1) = " << fmt(sp.bound) << u
            << ", free (the rest) = " << fmt(sp.free) << u
            << ", free / a1 = " << fmt(sp.free / fit.harmonics[0].amplitude) << "\n";
      }
    }
    spectrum = wv::welch_spectrum(base.t, base.eta.front(), sopt);
    const auto p = wv::spectral_parameters(spectrum.f, spectrum.S, band);
    rep << "spectrum (Welch: Hann taper, 50 % overlap, " << spectrum.segments << " segments of "
        << spectrum.segment_samples << " samples = " << fmt(spectrum.segment_samples * spectrum.dt)
        << " s, df = " << fmt(spectrum.df) << " Hz, linear detrend)\n";
    rep << "  variance " << fmt(spectrum.variance) << u << "^2; band " << band_text(band)
        << ": m0 = " << fmt(p.m0) << u << "^2\n";
    print_parameters(rep, p, u);
  }

  wv::ReflectionResult refl;
  if (!opt.reflection.empty()) {
    const std::size_t first = opt.gauge.empty() ? 0 : 1;
    const std::string u = unit_of(records[first]);
    wv::ReflectionOptions ropt;
    ropt.spectrum = sopt;
    ropt.band = band;
    ropt.g = opt.gravity;
    refl = wv::mansard_funke(base.t, {base.eta[first], base.eta[first + 1], base.eta[first + 2]}, x,
                             opt.depth, ropt);
    rep << "reflection (Mansard & Funke 1980; gauges " << records[first].column.name << ", "
        << records[first + 1].column.name << ", " << records[first + 2].column.name
        << " at x = " << fmt(x[0]) << ", " << fmt(x[1]) << ", " << fmt(x[2]) << " m; depth "
        << fmt(opt.depth) << " m; incident = travelling towards +x)\n";
    rep << "  band " << band_text(band) << ", " << refl.incident.bins
        << " frequencies, df = " << fmt(refl.df) << " Hz, " << refl.segments << " segments\n";
    rep << "  Hm0_incident = " << fmt(refl.hm0_incident) << u
        << ", Hm0_reflected = " << fmt(refl.hm0_reflected) << u << ", Kr = " << fmt(refl.kr)
        << "\n";
    rep << "  incident:";
    print_parameters(rep, refl.incident, u);
    if (!std::isnan(opt.period)) {
      const auto rr = wv::mansard_funke_regular(
          base.t, {base.eta[first], base.eta[first + 1], base.eta[first + 2]}, x, opt.depth,
          1.0 / opt.period, opt.gravity);
      rep << "  regular wave, T = " << fmt(opt.period)
          << " s (each gauge's first harmonic by least squares, the same separation at 1/T): "
             "a_incident = "
          << fmt(rr.a_incident) << u << ", a_reflected = " << fmt(rr.a_reflected) << u
          << ", Kr = " << fmt(rr.kr) << ", residual " << fmt(rr.residual) << u << "\n";
    }
    if (!refl.skipped.empty()) {
      // As ranges of consecutive frequencies: "0.01-0.15, 3.2 Hz".
      std::vector<std::string> ranges;
      for (std::size_t i = 0; i < refl.skipped.size();) {
        std::size_t j = i;
        while (j + 1 < refl.skipped.size() && refl.skipped[j + 1] - refl.skipped[j] < 1.5 * refl.df)
          ++j;
        ranges.push_back(fmt(refl.skipped[i]) + (j > i ? "-" + fmt(refl.skipped[j]) : ""));
        i = j + 1;
      }
      rep << "  skipped " << refl.skipped.size()
          << " frequencies (every gauge spacing near a multiple of L/2):";
      const std::size_t shown = std::min<std::size_t>(ranges.size(), 10);
      for (std::size_t i = 0; i < shown; ++i) rep << (i ? ", " : " ") << ranges[i];
      rep << (shown < ranges.size() ? ", ..." : "") << " Hz\n";
    }
  }

  if (!opt.csv.empty()) {
    std::ostringstream csv;
    csv << "# swell waves analyse " << opt.file << ": one-sided variance density spectra (Welch)\n"
        << provenance_text(capture_provenance(), "# ");
    auto density_unit = [](const Record& r) {
      return " [" + (r.column.unit.empty() ? std::string("1") : r.column.unit + "^2") + "/Hz]";
    };
    csv << "f [Hz]";
    if (!opt.gauge.empty())
      csv << ",S_" << records.front().column.name << density_unit(records.front());
    if (!opt.reflection.empty())
      csv << ",S_incident" << density_unit(records.back()) << ",S_reflected"
          << density_unit(records.back());
    csv << "\n";
    const auto& f = opt.gauge.empty() ? refl.f : spectrum.f;
    char buf[40];
    for (std::size_t k = 0; k < f.size(); ++k) {
      std::snprintf(buf, sizeof buf, "%.9g", f[k]);
      csv << buf;
      auto cell = [&](const std::vector<double>& v) {
        csv << ',';
        if (k < v.size() && std::isfinite(v[k])) {
          std::snprintf(buf, sizeof buf, "%.9g", v[k]);
          csv << buf;
        }
      };
      if (!opt.gauge.empty()) cell(spectrum.S);
      if (!opt.reflection.empty()) {
        cell(refl.S_incident);
        cell(refl.S_reflected);
      }
      csv << "\n";
    }
    write_file_atomically(opt.csv, csv.str());
    rep << "spectrum written to " << opt.csv << "\n";
  }
  out << rep.str();
}

Subcommand add_waves_analyse_command(CLI::App& waves) {
  auto opt = std::make_shared<WavesAnalyseOptions>();
  auto* a = waves.add_subcommand(
      "analyse", "analyse gauge records: zero crossing, harmonics, spectrum, reflection");
  a->add_option("file", opt->file, "gauge CSV (`time [s],H1 [m],...`)")->required();
  a->add_option("--gauge", opt->gauge, "column to analyse (name, with or without its unit)");
  a->add_option("--from", opt->from, "window start [s]");
  a->add_option("--to", opt->to, "window end [s]");
  auto* period = a->add_option("--period", opt->period,
                               "wave period [s]: fit its harmonics (with --reflection: also the "
                               "regular-wave separation at 1/T)");
  a->add_option("--harmonics", opt->harmonics, "harmonics fitted with --period (default 3)")
      ->needs(period);
  a->add_option("--crossing", opt->crossing, "zero crossing: up (default) or down")
      ->check(CLI::IsMember({"up", "down"}));
  a->add_option("--segment", opt->segment, "Welch segment length [s] (default: 8 segments)");
  auto* refl = a->add_option("--reflection", opt->reflection,
                             "three gauge columns G1,G2,G3 for the Mansard-Funke separation");
  auto* pos =
      a->add_option("--positions", opt->positions, "their positions x1,x2,x3 [m]")->needs(refl);
  auto* depth = a->add_option("--depth", opt->depth,
                              "water depth [m] (reflection; with --period: bound and free "
                              "second harmonic)");
  refl->needs(pos)->needs(depth);
  a->add_option("--fmin", opt->fmin, "band start [Hz] (spectral parameters and reflection)");
  a->add_option("--fmax", opt->fmax, "band end [Hz]");
  a->add_option("--gravity", opt->gravity, "g [m/s^2] (default 9.81)");
  a->add_option("--csv", opt->csv, "write the spectra to this CSV file");
  return Subcommand(a, [opt] {
    run_waves_analyse(*opt, std::cout);
    return 0;
  });
}

}  // namespace swell
