#include "apps/validate_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "apps/probe_command.hpp"
#include "case/reader.hpp"
#include "foam/foam.hpp"
#include "io/resources.hpp"
#include "run/run.hpp"
#include "validation/validation_manifest.hpp"
#include "validation/validation_report.hpp"
#include "validation/wave_theory.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

std::string now_utc() {
  return utc_minutes_now();
}

// The report's "How this report was made" section, and run_info.yaml beside it.
std::string provenance_section(const Provenance& p) {
  std::ostringstream o;
  o << "## How this report was made\n\n";
  for (const auto& [k, v] : p.fields()) o << "- " << k << ": `" << v << "`\n";
  return o.str();
}

void write_output_info(const std::string& dir, const std::string& kind, const Provenance& p) {
  RunInfo info;
  info.header = "how the files in this folder were produced (written by swell " + kind + ")";
  info.kind = kind;
  info.date = utc_minutes_now();
  info.provenance = {p};
  write_run_info(dir, info);
}

// How a result was made, for the runs table: the commit and date of the command that wrote
// it (its run_info.yaml), "recovered" entries as such, or "not recorded".
std::string made_by(const RunInfo& i) {
  if (i.provenance.empty()) return "not recorded";
  const Provenance& p = i.provenance.back();
  if (!p.recovered.empty()) return "recovered " + p.recovered.substr(0, p.recovered.find(';'));
  std::string c = p.commit.size() > 12 && p.commit.find_first_not_of("0123456789abcdef") >= 12
                      ? p.commit.substr(0, 12) + (p.commit.ends_with("-dirty") ? "-dirty" : "")
                      : p.commit;
  return "`" + c + "`, " + p.date;
}

std::string safe_file_name(const std::string& s) {
  std::string out;
  for (const char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-') ? c : '_';
  return out;
}

std::string seconds_text(double s) {
  if (!std::isfinite(s)) return "–";
  if (s < 120.0) return format_number(s, 3) + " s";
  return format_number(s / 60.0, 3) + " min";
}

bool has_gauges(const std::string& dir) {
  if (!fs::is_directory(dir)) return false;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("gauges_", 0) == 0 && e.path().extension() == ".csv") return true;
  }
  return false;
}

// The reference column for `gauge` in `table`: an explicit mapping, the gauge's own name, or
// a column ending in "_<gauge>"; "" if none.
std::string match_column(const SeriesTable& table, const std::string& gauge,
                         const std::map<std::string, std::string>& map) {
  if (const auto it = map.find(gauge); it != map.end()) return it->second;
  if (table.find(gauge) >= 0) return gauge;
  const std::string suffix = "_" + gauge;
  for (const auto& c : table.columns)
    if (c.size() > suffix.size() && c.compare(c.size() - suffix.size(), suffix.size(), suffix) == 0)
      return c;
  return "";
}

// What the figures show, for the reports' Plots section.
std::string plot_conventions() {
  return "References are black or grey (open markers for tables of points), runs coloured with "
         "their own line style and marker (legend: method and resolution, from each run's "
         "run_info.yaml). The grey band with dashed edges and the grey bar above the curves is "
         "the metric window, the orange bar the peak window; a y axis clipped to keep isolated "
         "spikes from squashing the curves says so in its corner.\n\n";
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace

std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      bool zero_allowed) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(v) || !(zero_allowed ? v >= 0.0 : v > 0.0))
        throw std::invalid_argument(item);
      out.push_back(v + 0.0);  // -0 as 0
    } catch (const std::exception&) {
      throw std::invalid_argument(option + ": '" + item + "' is not a number " +
                                  (zero_allowed ? ">= 0" : "> 0"));
    }
  }
  if (out.empty()) throw std::invalid_argument(option + ": expected numbers, got '" + text + "'");
  return out;
}

// ---------------------------------------------------------------------------------------------
// swell compare

CompareSummary run_compare(const CompareOptions& opt, std::ostream& log) {
  if (opt.runs.empty()) throw std::invalid_argument("compare: give at least one run folder");
  if (opt.reference.empty()) throw std::invalid_argument("compare: --reference FILE is required");
  if (opt.out_dir.empty()) throw std::invalid_argument("compare: -o DIR is required");
  if (!opt.labels.empty() && opt.labels.size() != opt.runs.size())
    throw std::invalid_argument("compare: " + std::to_string(opt.labels.size()) + " labels for " +
                                std::to_string(opt.runs.size()) + " runs");
  std::map<std::string, std::string> map;
  for (const auto& m : opt.map) {
    const auto eq = m.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == m.size())
      throw std::invalid_argument("--map '" + m + "': expected GAUGE=COLUMN");
    map[m.substr(0, eq)] = m.substr(eq + 1);
  }

  // The reference: a table, or a run whose gauge series are the columns.
  const bool ref_is_run = fs::is_directory(opt.reference);
  SeriesTable ref_table;
  std::vector<Series> ref_run;
  if (ref_is_run) {
    ref_run = read_run_gauges(opt.reference);
    ref_table.path = opt.reference;
    for (const auto& s : ref_run) ref_table.columns.push_back(s.name);
  } else {
    ref_table = read_series_table(opt.reference);
  }
  const std::string ref_name = fs::path(opt.reference).filename().string();

  std::vector<RunData> runs;
  std::vector<std::string> legends;  // plot legend: --labels, or method + resolution
  for (std::size_t i = 0; i < opt.runs.size(); ++i) {
    std::string label =
        opt.labels.empty() ? fs::path(opt.runs[i]).filename().string() : opt.labels[i];
    if (label.empty()) label = "run" + std::to_string(i + 1);
    runs.push_back(load_run(label, opt.runs[i]));
    legends.push_back(opt.labels.empty() ? run_display_label(runs.back().info, label) : label);
  }
  // Two runs of the same method and resolution: tell them apart by their folders.
  for (std::size_t i = 0; i < legends.size(); ++i)
    if (std::count(legends.begin(), legends.end(), legends[i]) > 1)
      for (std::size_t k = i; k < legends.size(); ++k)
        if (legends[k] == legends[i] && legends[k] != runs[k].label)
          legends[k] += " (" + runs[k].label + ")";
  std::string ref_legend = opt.reference_label;
  if (ref_legend.empty() && ref_is_run)
    ref_legend = run_display_label(read_run_info(opt.reference), ref_name) + " (reference)";

  Normalisation norm;
  norm.name = "compare";
  norm.time_scale = opt.time_scale;
  norm.value_scale = opt.value_scale;
  MetricRequest req;
  req.window = opt.window;
  req.peak = true;
  req.peak_window = opt.peak_window ? *opt.peak_window : opt.window;
  req.arrival = opt.arrival_threshold.has_value();
  req.arrival_threshold = opt.arrival_threshold.value_or(0.0);
  req.relative = true;

  std::vector<MetricRow> rows;
  std::vector<PlotSpec> plots;
  std::vector<std::string> gauges;  // in first-seen order
  for (const auto& r : runs)
    for (const auto& s : r.gauges)
      if (std::find(gauges.begin(), gauges.end(), s.name) == gauges.end()) gauges.push_back(s.name);
  std::vector<std::string> unmatched;
  for (const auto& g : gauges) {
    const std::string column = match_column(ref_table, g, map);
    if (column.empty()) {
      unmatched.push_back(g);
      continue;
    }
    Series ref;
    if (ref_is_run) {
      for (const auto& s : ref_run)
        if (s.name == column) ref = scaled(s, opt.time_scale, opt.value_scale);
    } else {
      ref = ref_table.series(column);
    }
    PlotSpec plot;
    plot.png = safe_file_name(g) + ".png";
    plot.title = g + " against " + ref_name;
    plot.xlabel = opt.time_scale == 1.0 ? "t [s]" : "t [s] x " + format_number(opt.time_scale, 5);
    std::string unit;  // the gauge's unit, from the first run that has it
    for (const auto& r : runs)
      if (const Series* s = r.find(g); s && unit.empty()) unit = s->unit;
    const std::string bracket = unit.empty() ? "" : " [" + unit + "]";
    plot.ylabel = opt.value_scale == 1.0 ? g + bracket
                                         : g + bracket + " x " + format_number(opt.value_scale, 5);
    plot.window = opt.window;
    plot.peak_window = opt.peak_window ? *opt.peak_window : Window{};
    PlotLine rl;
    rl.label = ref_legend.empty() ? ref_name + ", column " + column : ref_legend;
    rl.file = ref.source;
    rl.column = column;
    rl.reference = true;
    if (ref_is_run) {
      rl.time_scale = opt.time_scale;
      rl.value_scale = opt.value_scale;
    }
    plot.lines.push_back(rl);
    for (const auto& r : runs) {
      const Series* s = r.find(g);
      if (!s) continue;
      MetricRow row;
      row.run = r.label;
      row.kind = r.info.kind;
      row.resolution = r.info.resolution;
      row.gauge = g;
      row.reference = ref_name;
      row.reference_label = column;
      row.norm = norm;
      row.m = compute_metrics(scaled(*s, opt.time_scale, opt.value_scale), ref, req);
      rows.push_back(row);
      const std::string& legend = legends[static_cast<std::size_t>(&r - runs.data())];
      plot.lines.push_back({legend, s->source, g, opt.time_scale, opt.value_scale, false});
    }
    plots.push_back(plot);
  }
  if (rows.empty())
    throw std::invalid_argument("compare: no gauge of the runs has a column in " + opt.reference +
                                " (use --map GAUGE=COLUMN)");

  fs::create_directories(opt.out_dir);
  CompareSummary sum;
  sum.rows = static_cast<int>(rows.size());
  sum.metrics_csv = (fs::path(opt.out_dir) / "metrics.csv").string();
  write_metrics_csv(sum.metrics_csv, rows, "swell compare against " + opt.reference);
  std::string why;
  sum.plots = make_plots(plots, (fs::path(opt.out_dir) / "plots").string(), &why);
  if (!sum.plots) log << "compare: plots skipped: " << why << "\n";

  std::ostringstream md;
  md << "# Comparison against " << ref_name << "\n\n"
     << "Generated by `swell compare` on " << now_utc() << ". Reference: `" << opt.reference
     << "`.\n\n| run | legend | folder |\n|---|---|---|\n";
  for (std::size_t i = 0; i < runs.size(); ++i)
    md << "| " << runs[i].label << " | " << legends[i] << " | `" << runs[i].dir << "` |\n";
  md << "\nRun series scaled by t x " << format_number(opt.time_scale, 6) << ", value x "
     << format_number(opt.value_scale, 6) << "; metric window [" << format_number(opt.window.t0)
     << ", " << format_number(opt.window.t1) << "]. NRMSE = RMS difference at the reference "
     << "samples / reference peak-to-peak; relative errors |run - ref|/|ref| at the reference "
        "samples (for a reference that crosses zero: |run - ref| / its range, marked R); peaks are "
        "the maxima in the peak window.\n\n## Metrics\n\n"
     << markdown_metrics_table(rows) << "\n";
  if (!unmatched.empty()) {
    md << "Gauges without a reference column (not compared):";
    for (const auto& g : unmatched) md << " " << g;
    md << ".\n\n";
  }
  md << "## Plots\n\n";
  if (sum.plots) {
    md << plot_conventions();
    md << markdown_plot_list(plots, (fs::path(opt.out_dir) / "plots").string());
  } else {
    md << "Plots skipped: " << why << "\n";
  }
  const Provenance prov = capture_provenance();
  md << "\n" << provenance_section(prov);
  sum.report = (fs::path(opt.out_dir) / "report.md").string();
  write_text(sum.report, md.str());
  write_output_info(opt.out_dir, "compare", prov);
  log << "compare: " << rows.size() << " comparisons -> " << sum.metrics_csv << ", " << sum.report
      << "\n";
  return sum;
}

// ---------------------------------------------------------------------------------------------
// swell validate

namespace {

struct ValidationRun {
  RunData data;
  std::string source;  // "fresh" | "committed"
};

// Runs the SPH case at `dp` into `dir` and records run_info.yaml there.
void run_sph(const Manifest& m, double dp, double end_time, const std::string& dir, int threads,
             bool progress, std::ostream& log) {
  const CaseSpec spec = load_manifest_case(m, dp, end_time);
  log << "validate: SPH " << spec.name << " at dp = " << dp << " m -> " << dir << "\n";
  RunOptions ro;
  ro.out_dir = dir;
  ro.overwrite = true;  // validate owns its run folders
  ro.threads = threads;
  ro.progress = progress;
  std::ostringstream summary;
  ro.log = &summary;
  const RunSummary s = run_case(spec, ro);
  RunInfo info = read_run_info(dir);  // the run's own, with its provenance
  info.header = "how the gauge files next to this one were produced (written by swell validate)";
  info.kind = "sph";
  info.resolution = dp;
  info.wall_seconds = s.wall_seconds;
  info.size = static_cast<long>(s.fluid + s.boundary);
  info.end_time = s.sim_time;
  info.date = now_utc();
  info.note = std::to_string(s.fluid) + " fluid + " + std::to_string(s.boundary) +
              " boundary particles, " + std::to_string(s.steps) + " steps";
  write_run_info(dir, info);
}

// Runs interFoam at `cell` into `dir`/case and puts its gauges and run_info.yaml in `dir`.
void run_foam(const Manifest& m, double cell, double end_time, const std::string& dir, int np,
              std::ostream& log) {
  const CaseSpec spec = load_manifest_case(m, 0.0, end_time);
  FoamOptions fo;
  fo.out_dir = (fs::path(dir) / "case").string();
  fo.cell_size = cell;
  fo.run = true;
  fo.np = np;
  const double t_end = end_time > 0.0 ? end_time : (m.end_time ? *m.end_time : -1.0);
  fo.end_time = t_end;
  log << "validate: interFoam " << spec.name << " at " << cell << " m cells -> " << dir << "\n";
  const FoamResult r = run_foam_case(spec, fo, log);
  copy_results(r.gauge_dir, dir);
  RunInfo info;
  info.header = "how the gauge files next to this one were produced (written by swell validate)";
  info.provenance = {capture_provenance()};
  info.kind = "openfoam";
  info.resolution = cell;
  info.wall_seconds = r.wall_seconds;
  info.size = r.cells;
  info.end_time = r.end_time;
  info.date = now_utc();
  info.note =
      "interFoam, " + std::to_string(r.steps) + " steps, " + std::to_string(np) + " process(es)";
  write_run_info(dir, info);
}

bool target_applies(const ManifestTarget& t, const std::string& kind) {
  return t.runs == "all" || t.runs == kind;
}

std::string bound_text(const ManifestTarget& t) {
  std::string s;
  if (t.max_abs) s += "|v| <= " + format_number(*t.max_abs);
  if (t.max) s += std::string(s.empty() ? "" : ", ") + "v <= " + format_number(*t.max);
  if (t.min) s += std::string(s.empty() ? "" : ", ") + "v >= " + format_number(*t.min);
  return s;
}

bool target_met(const ManifestTarget& t, double v) {
  if (!std::isfinite(v)) return false;
  if (t.max_abs && std::abs(v) > *t.max_abs) return false;
  if (t.max && v > *t.max) return false;
  if (t.min && v < *t.min) return false;
  return true;
}

}  // namespace

ValidateSummary run_validate(const ValidateOptions& opt, std::ostream& log) {
  Manifest m = load_manifest(find_manifest(opt.name, opt.search_root));
  m.case_sets = opt.sets;
  // Nothing is written into an installed tree: committed results are updated in a checkout.
  if (opt.save_results && path_within(m.results_dir, installed_data_dir()))
    throw std::invalid_argument("--save-results would write into " + m.results_dir +
                                ", which is part of the installed share/swell: run it on a "
                                "source checkout (SWELL_HOME=CHECKOUT) to update its results");
  const std::string out = opt.out_dir.empty() ? "out/validate/" + m.name : opt.out_dir;
  fs::create_directories(out);
  ValidateSummary sum;

  std::vector<double> dps = opt.resolutions.empty() ? m.sph_resolutions : opt.resolutions;
  if (dps.empty()) dps.push_back(load_manifest_case(m).dp);
  const std::vector<double> cells = opt.cell_sizes.empty() ? m.foam_cell_sizes : opt.cell_sizes;

  std::vector<ValidationRun> runs;
  auto take = [&](const std::string& label, const std::string& fresh, bool ran) {
    const std::string committed = (fs::path(m.results_dir) / label).string();
    if (ran && has_gauges(fresh)) {
      if (opt.save_results) {
        copy_results(fresh, committed);
        log << "validate: saved " << label << " -> " << committed << "\n";
      }
      runs.push_back({load_run(label, fresh), "fresh"});
    } else if (has_gauges(committed)) {
      runs.push_back({load_run(label, committed), "committed"});
    } else {
      sum.notes.push_back("no results for " + label + " (neither run now nor committed in " +
                          committed + ")");
    }
  };

  for (const double dp : dps) {
    const std::string label = sph_label(dp), dir = (fs::path(out) / "runs" / label).string();
    bool ran = false;
    if (opt.run_sph) {
      try {
        run_sph(m, dp, opt.end_time, dir, opt.threads, opt.progress, log);
        ran = true;
      } catch (const InstabilityError& e) {
        const std::string note =
            "SPH at dp = " + format_number(dp) + " m went unstable: " + e.what();
        log << "validate: " << note << "\n";
        sum.notes.push_back(note);
      }
    }
    take(label, dir, ran);
  }
  bool foam_ok = opt.run_foam;
  if (opt.run_foam && !cells.empty()) {
    std::string why;
    if (!openfoam_available(&why)) {
      foam_ok = false;
      const std::string note = "--run-foam: OpenFOAM is not available here (" + why +
                               "); the committed OpenFOAM results are used instead";
      log << "validate: " << note << "\n";
      sum.notes.push_back(note);
    }
  }
  for (const double cell : cells) {
    const std::string label = foam_label(cell), dir = (fs::path(out) / "runs" / label).string();
    bool ran = false;
    if (foam_ok) {
      try {
        run_foam(m, cell, opt.end_time, dir, opt.np, log);
        ran = true;
      } catch (const FoamError& e) {
        const std::string note = "interFoam at " + format_number(cell) + " m failed: " + e.what();
        log << "validate: " << note << "\n";
        sum.notes.push_back(note);
      }
    }
    take(label, dir, ran);
  }

  // The finest OpenFOAM result is the "openfoam" reference of the SPH runs (and of the
  // coarser OpenFOAM runs: mesh convergence).
  const ValidationRun* finest_foam = nullptr;
  for (const auto& r : runs)
    if (r.data.info.kind == "openfoam" &&
        (!finest_foam || r.data.info.resolution < finest_foam->data.info.resolution))
      finest_foam = &r;

  std::map<std::string, SeriesTable> tables;
  auto table = [&](const std::string& file) -> const SeriesTable& {
    auto it = tables.find(file);
    if (it == tables.end()) it = tables.emplace(file, read_series_table(file)).first;
    return it->second;
  };

  // Theory references (validation/wave_theory.hpp): one CSV per gauge in OUT/theory/, sampled
  // at the case's gauge interval (else 1/200 of the run) to the validated end time.
  std::optional<CaseSpec> theory_case;
  auto write_theory = [&](const std::string& gauge) {
    if (!theory_case) theory_case = load_manifest_case(m, 0.0, opt.end_time);
    const CaseSpec& c = *theory_case;
    const double dt = c.gauge_every > 0.0 ? c.gauge_every : c.t_end / 200.0;
    Series th;
    try {
      th = paddle_theory_series(c, gauge, dt, c.t_end);
    } catch (const std::invalid_argument& e) {
      throw ManifestError(m.file + ": references: " + e.what());
    }
    const fs::path dir = fs::path(out) / "theory";
    fs::create_directories(dir);
    const fs::path file = dir / (safe_file_name(gauge) + ".csv");
    std::ofstream f(file);
    f << "# swell validate " << m.name << ": wave-paddle theory at gauge " << gauge
      << " (validation/wave_theory.hpp)\ntime [s]," << gauge << " [m]\n";
    f.precision(10);
    for (std::size_t i = 0; i < th.t.size(); ++i) f << th.t[i] << "," << th.v[i] << "\n";
    if (!f) throw std::runtime_error("cannot write " + file.string());
    return file.string();
  };

  std::vector<MetricRow> rows;
  std::vector<PlotSpec> plots;
  for (const auto& g : m.gauges) {
    const Normalisation& norm = m.normalisations.at(g.normalisation);
    PlotSpec plot;
    plot.png = safe_file_name(g.gauge) + ".png";
    plot.title = m.title + ": " + g.gauge;
    std::string unit;  // the gauge's unit, from the first run that has it
    for (const auto& r : runs)
      if (const Series* s = r.data.find(g.gauge); s && unit.empty()) unit = s->unit;
    plot.xlabel = axis_label(norm.time_label, "s", norm.time_scale);
    plot.ylabel =
        axis_label(norm.value_label.empty() ? g.gauge : norm.value_label, unit, norm.value_scale);
    plot.window = g.request.window;
    if (g.request.peak) plot.peak_window = g.request.peak_window;
    std::vector<std::pair<std::string, Series>> refs;  // (reference name, normalised series)
    for (const auto& [ref_name, column] : g.columns) {
      const ManifestReference* ref = m.reference(ref_name);
      if (!ref->theory.empty()) {
        // The case's paddle theory at gauge `column`, written beside the report (the plot
        // reads it from there) in the gauges' units, then normalised like a run.
        const std::string file = write_theory(column);
        refs.emplace_back(ref_name,
                          scaled(table(file).series(column), norm.time_scale, norm.value_scale));
        plot.lines.push_back({ref->label, file, column, norm.time_scale, norm.value_scale, false});
        continue;
      }
      refs.emplace_back(ref_name, table(ref->file).series(column));
      plot.lines.push_back({ref->label, ref->file, column, 1.0, 1.0, true});
    }
    for (const auto& r : runs) {
      const Series* s = r.data.find(g.gauge);
      if (!s) {
        sum.notes.push_back(r.data.label + " has no gauge " + g.gauge);
        continue;
      }
      const Series run_norm = scaled(*s, norm.time_scale, norm.value_scale);
      plot.lines.push_back({run_display_label(r.data.info, r.data.label), s->source, g.gauge,
                            norm.time_scale, norm.value_scale, false});
      MetricRow base;
      base.run = r.data.label;
      base.kind = r.data.info.kind;
      base.resolution = r.data.info.resolution;
      base.gauge = g.gauge;
      base.norm = norm;
      for (const auto& [ref_name, ref_series] : refs) {
        MetricRow row = base;
        row.reference = ref_name;
        row.reference_label = m.reference(ref_name)->label;
        row.m = compute_metrics(run_norm, ref_series, g.request);
        rows.push_back(row);
      }
      if (finest_foam && &r != finest_foam) {
        if (const Series* f = finest_foam->data.find(g.gauge)) {
          MetricRow row = base;
          row.reference = "openfoam";
          row.reference_label = finest_foam->data.label;
          row.m =
              compute_metrics(run_norm, scaled(*f, norm.time_scale, norm.value_scale), g.request);
          rows.push_back(row);
        }
      }
    }
    plots.push_back(plot);
  }

  // Targets: every applicable run, reported, never used to change anything.
  struct TargetResult {
    const ManifestTarget* t;
    std::string run;
    double value;
    bool pass, known;
  };
  std::vector<TargetResult> target_results;
  for (const auto& t : m.targets) {
    bool any = false;
    for (const auto& row : rows) {
      if (row.gauge != t.gauge || row.reference != t.against || !target_applies(t, row.kind))
        continue;
      const double v = row_value(row, t.metric);
      const bool pass = target_met(t, v);
      const bool known = std::find(t.known_failures.begin(), t.known_failures.end(), row.run) !=
                         t.known_failures.end();
      target_results.push_back({&t, row.run, v, pass, known});
      (pass ? sum.targets_pass : sum.targets_fail)++;
      const std::string what = t.text + ": " + row.run + " " + t.metric + " = " + format_number(v);
      if (!pass && known) sum.targets_known_fail++;
      if (!pass && !known)
        sum.unexpected_failures.push_back(what + " (bound " + bound_text(t) + ")");
      if (pass && known)
        sum.stale_known_failures.push_back(what + " meets it but is listed in known_failures");
      any = true;
    }
    if (!any) {
      target_results.push_back({&t, "", std::numeric_limits<double>::quiet_NaN(), false, false});
      sum.targets_missing++;
    }
  }

  sum.rows = static_cast<int>(rows.size());
  sum.metrics_csv = (fs::path(out) / "metrics.csv").string();
  write_metrics_csv(sum.metrics_csv, rows, "swell validate " + m.name + ": " + m.title);
  std::string why;
  sum.plots = make_plots(plots, (fs::path(out) / "plots").string(), &why);
  if (!sum.plots) {
    log << "validate: plots skipped: " << why << "\n";
    sum.notes.push_back("plots skipped: " + why);
  }

  // The one-page report.
  std::ostringstream md;
  md << "# Validation: " << m.title << "\n\n"
     << "Generated by `swell validate " << m.name << "` on " << now_utc() << ". Case `"
     << m.case_file << "`, manifest `" << m.file << "`.\n\n";
  if (!m.notes.empty()) md << m.notes << "\n\n";
  md << "## Runs\n\n| run | solver | resolution [m] | particles / cells | simulated [s] | "
        "wall time | results | legend | made by |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : runs) {
    const RunInfo& i = r.data.info;
    md << "| " << r.data.label << " | " << (i.kind == "openfoam" ? "interFoam" : "SPH") << " | "
       << format_number(i.resolution, 4) << " | " << i.size << " | " << format_number(i.end_time, 3)
       << " | " << seconds_text(i.wall_seconds) << " | " << r.source << " | "
       << run_display_label(i, r.data.label) << " | " << made_by(i) << " |\n";
  }
  md << "\n";
  if (!m.targets.empty()) {
    md << "## Targets (reported, not tuned to)\n\n| target | gauge | against | run | metric | "
          "value | bound | result |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& tr : target_results) {
      md << "| " << tr.t->text << " | " << tr.t->gauge << " | " << tr.t->against << " | "
         << (tr.run.empty() ? "–" : tr.run) << " | " << tr.t->metric << " | "
         << format_number(tr.value) << " | " << bound_text(*tr.t) << " | "
         << (tr.run.empty() ? "no result"
                            : (tr.pass ? "pass" : (tr.known ? "**fail** (known)" : "**fail**")))
         << " |\n";
    }
    md << "\n";
  }
  md << "## Metrics\n\n";
  for (const auto& [key, n] : m.normalisations)
    md << "- `" << key << "`: " << n.time_label << ", " << n.value_label << "\n";
  md << "\nNRMSE = RMS(run - reference) at the reference samples in the gauge's window / the "
        "reference's peak-to-peak range there; peaks are the maxima in the peak window (error "
        "relative to the reference peak); arrival = first crossing of the threshold; relative "
        "errors = |run - ref|/|ref| at the reference samples (for a reference that crosses zero: "
        "|run - ref| / its range, marked R). `openfoam` = the finest interFoam "
        "run. All values normalised; time errors in seconds.\n\n"
     << markdown_metrics_table(rows) << "\n## Plots\n\n";
  if (sum.plots) {
    md << plot_conventions();
    md << markdown_plot_list(plots, (fs::path(out) / "plots").string());
  } else {
    md << "Plots skipped: " << why << "\n\n";
  }
  if (!sum.notes.empty()) {
    md << "## Notes\n\n";
    for (const auto& n : sum.notes) md << "- " << n << "\n";
  }
  const Provenance prov = capture_provenance();
  md << "\n" << provenance_section(prov);
  sum.report = (fs::path(out) / "report.md").string();
  write_text(sum.report, md.str());
  write_output_info(out, "validate", prov);
  log << "validate " << m.name << ": " << runs.size() << " runs, " << rows.size()
      << " comparisons; targets: " << sum.targets_pass << " pass, " << sum.targets_fail << " fail ("
      << sum.targets_known_fail << " known), " << sum.targets_missing << " without result -> "
      << sum.report << "\n";
  return sum;
}

Subcommand add_compare_command(CLI::App& app) {
  struct Options {
    CompareOptions cmp;
    std::string labels, window, peak_window;
    double arrival = 0.0;
    CLI::Option* arrival_opt = nullptr;
  };
  auto o = std::make_shared<Options>();
  CompareOptions& cmp = o->cmp;
  auto* compare = app.add_subcommand(
      "compare", "metrics, plots and a report of runs' gauges against a reference CSV or run");
  compare->add_option("runs", cmp.runs, "run folders holding gauges_*.csv")->required();
  compare->add_option("--reference", cmp.reference, "reference CSV table, or a run folder")
      ->required();
  compare->add_option("--labels", o->labels, "comma-separated labels, one per run");
  compare->add_option("--reference-label", cmp.reference_label,
                      "legend text of the reference (e.g. \"experiment (Lobovsky 2014)\")");
  compare->add_option("-o,--out", cmp.out_dir, "output folder")->required();
  compare->add_option("--map", cmp.map, "GAUGE=COLUMN: reference column of a gauge (repeatable)");
  compare->add_option("--time-scale", cmp.time_scale, "normalise run times: t * scale")
      ->check(positive_check());
  compare->add_option("--value-scale", cmp.value_scale, "normalise run values: v * scale")
      ->check(positive_check());
  compare->add_option("--window", o->window, "metric window t0,t1 (scaled time)");
  compare->add_option("--peak-window", o->peak_window, "peak window t0,t1 (default: --window)");
  o->arrival_opt = compare->add_option("--arrival", o->arrival, "arrival threshold (scaled value)");
  return Subcommand(compare, [o] {
    auto window = [](const std::string& text, const std::string& option) {
      const auto v = parse_vector_option(text, option);
      if (!(v[1] > v[0]) || v[2] != 0.0)
        throw std::invalid_argument(option + ": expected t0,t1 with t1 > t0");
      return Window{v[0], v[1]};
    };
    CompareOptions cmp = o->cmp;
    if (!o->labels.empty()) {
      std::stringstream in(o->labels);
      for (std::string l; std::getline(in, l, ',');) cmp.labels.push_back(l);
    }
    if (!o->window.empty()) cmp.window = window(o->window, "--window");
    if (!o->peak_window.empty()) cmp.peak_window = window(o->peak_window, "--peak-window");
    if (*o->arrival_opt) cmp.arrival_threshold = o->arrival;
    run_compare(cmp, std::cerr);
    return 0;
  });
}

Subcommand add_validate_command(CLI::App& app) {
  struct Options {
    ValidateOptions val;
    std::string resolutions, cells;
  };
  auto o = std::make_shared<Options>();
  ValidateOptions& val = o->val;
  auto* validate = app.add_subcommand(
      "validate", "run/compare a validation case (validation/NAME/validation.yaml) and report");
  validate->add_option("name", val.name, "validation case name, folder or manifest file")
      ->required();
  add_set_option(validate, val.sets);
  validate->add_flag("--run-sph", val.run_sph, "run the SPH case (else: committed results)");
  validate->add_flag("--run-foam", val.run_foam, "run interFoam (else: committed results)");
  validate->add_option("--resolution", o->resolutions,
                       "SPH dp list d1,d2 [m] (default: manifest's)");
  validate->add_option("--cell-size", o->cells, "OpenFOAM cell sizes c1,c2 [m]");
  validate->add_option("-o,--out", val.out_dir, "output folder (default: out/validate/NAME)");
  validate->add_option("-t,--threads", val.threads, "OpenMP threads for SPH runs")
      ->check(count_check());
  validate->add_option("--np", val.np, "OpenFOAM processes")->check(count_check());
  validate->add_option("--end", val.end_time, "end time of fresh runs [s] (shortened runs)")
      ->check(positive_check());
  validate->add_flag("--save-results", val.save_results,
                     "copy fresh results into validation/NAME/results/ (to commit them)");
  return Subcommand(validate, [o] {
    ValidateOptions val = o->val;
    if (!o->resolutions.empty())
      val.resolutions = parse_number_list(o->resolutions, "--resolution");
    if (!o->cells.empty()) val.cell_sizes = parse_number_list(o->cells, "--cell-size");
    run_validate(val, std::cerr);
    return 0;
  });
}

}  // namespace swell
