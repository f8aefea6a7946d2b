// Plots and error conventions of `swell validate` / `swell compare` (issue #17): references
// that cross zero get range-normalised errors and no percentages; legend labels come from each
// run's run_info.yaml ("SPH dp 10 mm", "interFoam 5 mm cells"); axis labels carry units; every
// PNG has an SVG beside it whose text holds the run labels and the axis units. The plot checks
// run the real report path with validation/plot_validation.py and are skipped, saying why,
// where no python3 with matplotlib is installed.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "apps/validate_command.hpp"
#include "validation/metrics.hpp"
#include "validation/validation_report.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

constexpr double kTwoPi = 6.28318530717958647692;

// v = offset + amplitude sin(2 pi t) on [0, 2], every dt.
Series wave(double offset, double amplitude, double dt) {
  Series s;
  s.name = "eta";
  for (int i = 0; i * dt <= 2.0 + 1e-12; ++i) {
    s.t.push_back(i * dt);
    s.v.push_back(offset + amplitude * std::sin(kTwoPi * i * dt));
  }
  return s;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void put(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

TEST(Plots, ZeroCrossingIsDetectedWithATolerance) {
  EXPECT_TRUE(crosses_zero(wave(0.0, 1.0, 0.01), Window{}));
  // Positive, or dipping below zero by less than 5 % of the range: not crossing.
  EXPECT_FALSE(crosses_zero(wave(2.0, 1.0, 0.01), Window{}));
  EXPECT_FALSE(crosses_zero(wave(0.96, 1.0, 0.01), Window{}));  // min -0.04 = -2 % of 2
  EXPECT_TRUE(crosses_zero(wave(0.8, 1.0, 0.01), Window{}));    // min -0.2 = -10 %
  // Only the window counts: the positive first quarter period of a sine does not cross.
  EXPECT_FALSE(crosses_zero(wave(0.0, 1.0, 0.01), Window{0.0, 0.5}));
  EXPECT_NEAR(window_range(wave(0.0, 1.0, 0.01), Window{}), 2.0, 1e-9);
  EXPECT_TRUE(std::isnan(window_range(wave(0.0, 1.0, 0.01), Window{5.0, 6.0})));
}

TEST(Plots, ZeroCrossingReferenceGetsRangeErrorsNotPercentages) {
  // run = ref + 0.1, ref = sin(2 pi t): |run - ref| / R = 0.1 / 2 at every sample.
  const Series ref = wave(0.0, 1.0, 0.01);
  const Series run = wave(0.1, 1.0, 0.01);
  MetricRequest req;
  req.relative = true;
  req.peak = true;
  req.peak_window = Window{0.0, 1.0};
  req.mean = true;
  req.mean_window = Window{0.0, 1.0};
  req.impulse = true;
  req.impulse_window = Window{0.0, 1.0};
  const GaugeMetrics m = compute_metrics(run, ref, req);
  EXPECT_TRUE(m.crosses_zero);
  EXPECT_NEAR(m.ref_range, 2.0, 1e-9);
  EXPECT_NEAR(m.mean_abs_range_error, 0.05, 1e-9);
  EXPECT_NEAR(m.max_abs_range_error, 0.05, 1e-9);
  EXPECT_NEAR(m.peak_range_error, 0.05, 1e-9);
  EXPECT_NEAR(m.mean_range_error, 0.05, 1e-9);     // means over whole periods: 0.1 and 0
  EXPECT_NEAR(m.impulse_range_error, 0.05, 1e-9);  // impulses 0.1 and 0 over 1 s, / (2 x 1)
  for (const char* name : {"mean_rel_error", "max_rel_error", "peak_error", "mean_error",
                           "impulse_error", "mean_signed_rel_error"})
    EXPECT_TRUE(std::isnan(metric_value(m, name))) << name;
  EXPECT_EQ(metric_value(m, "crosses_zero"), 1.0);

  // A positive signal keeps its relative errors, and has the range errors too.
  const GaugeMetrics p = compute_metrics(wave(3.1, 1.0, 0.01), wave(3.0, 1.0, 0.01), req);
  EXPECT_FALSE(p.crosses_zero);
  EXPECT_NEAR(p.peak_error, 0.1 / 4.0, 1e-9);
  EXPECT_NEAR(p.peak_range_error, 0.05, 1e-9);
  EXPECT_GT(p.rel.mean_abs, 0.0);
  EXPECT_EQ(metric_value(p, "crosses_zero"), 0.0);

  // The report table writes the crossing row's errors as fractions of R, never as %.
  MetricRow row;
  row.run = "sph_dp0.01";
  row.gauge = "eta";
  row.reference = "experiment";
  row.m = m;
  const std::string md = markdown_metrics_table({row});
  const std::string line = md.substr(0, md.find('\n', md.find("| eta |")));
  EXPECT_EQ(line.find('%', line.find("| eta |")), std::string::npos) << md;
  EXPECT_NE(line.find("0.05 R"), std::string::npos) << md;
  EXPECT_NE(md.find("cross zero"), std::string::npos) << md;
}

TEST(Plots, LabelsFromRunInfoAndUnitsOnAxes) {
  EXPECT_EQ(length_text(0.004), "4 mm");
  EXPECT_EQ(length_text(0.0075), "7.5 mm");
  EXPECT_EQ(length_text(0.0028575), "2.86 mm");
  EXPECT_EQ(length_text(0.25), "0.25 m");
  RunInfo sph;
  sph.kind = "sph";
  sph.resolution = 0.004;
  EXPECT_EQ(run_display_label(sph, "sph_dp0.004"), "SPH dp 4 mm");
  RunInfo foam;
  foam.kind = "openfoam";
  foam.resolution = 0.005;
  EXPECT_EQ(run_display_label(foam, "foam_dx0.005"), "interFoam 5 mm cells");
  EXPECT_EQ(run_display_label(RunInfo{}, "my_run"), "my_run");
  EXPECT_EQ(axis_label("p [Pa]", "Pa", 1.0), "p [Pa]");
  EXPECT_EQ(axis_label("F_x", "N/m", 1.0), "F_x [N/m]");
  EXPECT_EQ(axis_label("p* = p/(rho g H)", "Pa", 3.4e-4), "p* = p/(rho g H) [-]");
}

// A validation folder whose only gauge, eta [m], oscillates about zero: SPH at 10 mm (0.02 m
// above the reference) and interFoam at 5 mm cells.
fs::path wave_validation(const fs::path& root) {
  auto gauges = [](double offset) {
    std::ostringstream csv;
    csv << "# swell gauges, case wavy\ntime [s],eta [m]\n";
    for (int i = 0; i <= 400; ++i)
      csv << 0.005 * i << "," << offset + 0.05 * std::sin(kTwoPi * 0.005 * i) << "\n";
    return csv.str();
  };
  put(root / "cases" / "wavy.yaml",
      "name: wavy\ndim: 2\ndp: 0.01\ntime: {end: 0.1}\nbodies:\n"
      "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}}\n"
      "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.2, 0.2]}}}\n"
      "gauges:\n  - {name: eta, kind: height, at: [0.5, 0.0]}\n");
  std::ostringstream ref;
  ref << "# synthetic wave record\nt,eta_lab\n";
  for (int i = 0; i <= 80; ++i)
    ref << 0.025 * i << "," << 0.05 * std::sin(kTwoPi * 0.025 * i) << "\n";
  const fs::path v = root / "validation" / "wavy";
  put(v / "lab.csv", ref.str());
  put(v / "results" / "sph_dp0.01" / "gauges_height.csv", gauges(0.02));
  put(v / "results" / "sph_dp0.01" / "run_info.yaml", "kind: sph\nresolution: 0.01\nsize: 400\n");
  put(v / "results" / "foam_dx0.005" / "gauges_height.csv", gauges(-0.01));
  put(v / "results" / "foam_dx0.005" / "run_info.yaml",
      "kind: openfoam\nresolution: 0.005\nsize: 9000\n");
  put(v / "validation.yaml",
      "title: wavy check\ncase: ../../cases/wavy.yaml\n"
      "normalisation:\n  eta: {time_scale: 1, value_scale: 1, value_label: eta}\n"
      "references:\n  - {name: experiment, file: lab.csv, label: \"experiment (wave lab 2026)\"}\n"
      "gauges:\n  - {gauge: eta, normalisation: eta, reference: {experiment: eta_lab},\n"
      "     window: [0.25, 1.75], peak_window: [0.0, 1.0], relative: true}\n"
      "runs:\n  sph: {resolutions: [0.01]}\n  openfoam: {cell_sizes: [0.005]}\n");
  return v;
}

// Points the report at this checkout's script, so the test does not depend on where the
// binary looks for it.
bool plots_possible(std::string* why) {
  const fs::path script = fs::path(SWELL_SOURCE_DIR) / "validation" / "plot_validation.py";
  setenv("SWELL_PLOT_SCRIPT", script.c_str(), 1);
  if (find_plot_python().empty()) {
    *why = "no python3 with matplotlib and numpy here (install python3-matplotlib)";
    return false;
  }
  return true;
}

TEST(Plots, ValidateReportOfAZeroCrossingSignal) {
  const fs::path root = fs::path(SWELL_BINARY_DIR) / "test_plots" / "validate";
  fs::remove_all(root);
  wave_validation(root);
  std::string why;
  const bool can_plot = plots_possible(&why);
  ValidateOptions opt;
  opt.name = "wavy";
  opt.search_root = root.string();
  opt.out_dir = (root / "out").string();
  std::ostringstream log;
  const ValidateSummary s = run_validate(opt, log);
  EXPECT_EQ(s.rows, 3);  // two runs against the lab, SPH against interFoam

  // No percent error anywhere in the metrics table: the reference crosses zero.
  const std::string report = slurp(root / "out" / "report.md");
  const std::string table = report.substr(report.find("| gauge | run |"));
  for (std::size_t at = table.find("| eta |"); at != std::string::npos;
       at = table.find("| eta |", at + 1)) {
    const std::string line = table.substr(at, table.find('\n', at) - at);
    EXPECT_EQ(line.find('%'), std::string::npos) << line;
    EXPECT_NE(line.find(" R |"), std::string::npos) << line;
  }
  const std::string csv = slurp(root / "out" / "metrics.csv");
  EXPECT_NE(csv.find("crosses_zero"), std::string::npos);
  // The run table gives each run's legend label.
  EXPECT_NE(report.find("| SPH dp 10 mm |"), std::string::npos) << report;
  EXPECT_NE(report.find("| interFoam 5 mm cells |"), std::string::npos) << report;

  if (!can_plot) GTEST_SKIP() << "plot checks skipped: " << why;
  ASSERT_TRUE(s.plots) << log.str();
  const fs::path png = root / "out" / "plots" / "eta.png";
  const fs::path svg = root / "out" / "plots" / "eta.svg";
  ASSERT_TRUE(fs::exists(png));
  ASSERT_TRUE(fs::exists(svg)) << "no SVG beside " << png;
  EXPECT_LT(fs::file_size(svg), 1000000u);
  const std::string text = slurp(svg);
  for (const char* label : {"SPH dp 10 mm", "interFoam 5 mm cells", "experiment (wave lab 2026)",
                            "metric window", "peak window", "eta [m]", "t [s]"})
    EXPECT_NE(text.find(label), std::string::npos) << label << " not in " << svg;
  EXPECT_NE(report.find("](plots/eta.svg)"), std::string::npos) << report;
}

TEST(Plots, CompareLegendsFromRunInfoAndReferenceLabel) {
  const fs::path root = fs::path(SWELL_BINARY_DIR) / "test_plots" / "compare";
  fs::remove_all(root);
  const fs::path v = wave_validation(root);
  std::string why;
  const bool can_plot = plots_possible(&why);
  CompareOptions opt;
  opt.runs = {(v / "results" / "sph_dp0.01").string(), (v / "results" / "foam_dx0.005").string()};
  opt.reference = (v / "lab.csv").string();
  opt.reference_label = "experiment (wave lab 2026)";
  opt.map = {"eta=eta_lab"};
  opt.value_scale = 20.0;  // eta / 0.05 m
  opt.out_dir = (root / "out").string();
  std::ostringstream log;
  const CompareSummary s = run_compare(opt, log);
  EXPECT_EQ(s.rows, 2);
  const std::string report = slurp(root / "out" / "report.md");
  EXPECT_NE(report.find("| sph_dp0.01 | SPH dp 10 mm |"), std::string::npos) << report;
  if (!can_plot) GTEST_SKIP() << "plot checks skipped: " << why;
  ASSERT_TRUE(s.plots) << log.str();
  const std::string text = slurp(root / "out" / "plots" / "eta.svg");
  for (const char* label : {"SPH dp 10 mm", "interFoam 5 mm cells", "experiment (wave lab 2026)",
                            "eta [m] x 20", "t [s]"})
    EXPECT_NE(text.find(label), std::string::npos) << label;
}

// The other figures: `swell bench --sweep`'s scaling plot and the Synolakis runup plot, drawn
// from the committed tables into a scratch folder.
TEST(Plots, BenchAndRunupScriptsWriteSvgWithUnitsAndLabels) {
  std::string why;
  if (!plots_possible(&why)) GTEST_SKIP() << "plot checks skipped: " << why;
  const std::string python = find_plot_python();
  const fs::path src(SWELL_SOURCE_DIR);
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_plots" / "scripts";
  fs::remove_all(d);
  fs::create_directories(d);
  const std::string scaling = "'" + python + "' '" + (src / "bench" / "plot_scaling.py").string() +
                              "' '" + (src / "bench" / "results" / "scaling.csv").string() + "' '" +
                              (d / "scaling.png").string() + "'";
  ASSERT_EQ(std::system(scaling.c_str()), 0) << scaling;
  ASSERT_TRUE(fs::exists(d / "scaling.svg"));
  const std::string bench = slurp(d / "scaling.svg");
  for (const char* text : {"wall time per particle-step [ns]", "particles N [count, log scale]",
                           "interaction phase, per particle"})
    EXPECT_NE(bench.find(text), std::string::npos) << text;

  const fs::path lab = src / ".." / "shared" / "reference" / "synolakis_1987_runup_lab.csv";
  if (!fs::exists(lab)) GTEST_SKIP() << "runup plot skipped: no " << lab;
  fs::copy_file(src / "validation" / "synolakis" / "results" / "runup_table.csv",
                d / "runup_table.csv");
  const std::string runup =
      "'" + python + "' '" + (src / "validation" / "synolakis" / "runup_table.py").string() +
      "' --lab '" + lab.string() + "' --replot '" + (d / "runup_table.csv").string() + "'";
  ASSERT_EQ(std::system(runup.c_str()), 0) << runup;
  const std::string svg = slurp(d / "runup.svg");
  for (const char* text :
       {"Swell SPH dp 6 mm (coefh 1, laminar), R max", "experiment (Synolakis 1987, lab points)",
        "H/d, wave height / depth [-]", "R/d, maximum runup / depth [-]"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  // Bad input: exit 2 with the reason.
  const std::string bad = runup.substr(0, runup.find(" --replot")) + " --replot '" +
                          (d / "missing.csv").string() + "' 2> /dev/null";
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), 2);
}

// The rows of a script's CSV table (header skipped) by their first cell; each must have `cells`
// cells (an empty map, which the callers' size checks catch, if one has not).
std::map<std::string, std::vector<std::string>> csv_rows_by_first_cell(const fs::path& file,
                                                                       std::size_t cells) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // header
  std::map<std::string, std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> row;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) row.push_back(c);
    if (row.size() != cells) {
      ADD_FAILURE() << file << ": " << row.size() << " cells, expected " << cells << ": " << line;
      return {};
    }
    rows[row[0]] = row;
  }
  return rows;
}

// validation/wave_flume2d/bound_long_wave.py on synthetic gauges whose long waves are known:
// the bound wave itself (ratio 1, nothing free), the bound wave of waves 10 % low (ratio 0.81,
// 1 against the measured amplitudes) and the bound wave plus a free one as large (1 not bound).
TEST(Plots, BoundLongWaveScriptReadsKnownLongWaves) {
  constexpr double kPi = std::numbers::pi;
  std::string why;
  if (!plots_possible(&why)) GTEST_SKIP() << "plot checks skipped: " << why;
  const std::string python = find_plot_python();
  const fs::path src(SWELL_SOURCE_DIR);
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_plots" / "bound_long_wave";
  fs::remove_all(d);
  const double w1 = 2 * kPi * 0.65, w2 = 2 * kPi * 0.80, a1 = 0.02, a2 = 0.018, b = 0.0018;
  const auto linear = [&](double t) { return a1 * std::cos(w1 * t) + a2 * std::cos(w2 * t + 1); };
  const auto bound = [&](double t) { return b * std::cos((w2 - w1) * t + 1.0); };
  {
    fs::create_directories(d);
    std::ofstream tgt(d / "target.csv");
    tgt << "# synthetic\ntime [s],eta_1.86 [m],eta_bound_1.86 [m]\n";
    for (int i = 0; i <= 2000; ++i) {
      const double t = 0.01 * i;
      tgt << t << "," << linear(t) + bound(t) << "," << bound(t) << "\n";
    }
  }
  const auto run = [&](const std::string& name, double scale, double free) {
    fs::create_directories(d / name);
    std::ofstream g(d / name / "gauges_height.csv");
    g << "# swell gauges\ntime [s],eta_2m [m]\n";
    for (int i = 0; i <= 2000; ++i) {
      const double t = 0.01 * i;
      g << t << ","
        << 0.4 + scale * linear(t) + scale * scale * bound(t) + free * std::cos((w2 - w1) * t - 0.5)
        << "\n";
    }
  };
  run("exact", 1.0, 0.0);
  run("low", 0.9, 0.0);
  run("free", 1.0, b);
  const std::string cmd = "'" + python + "' '" +
                          (src / "validation" / "wave_flume2d" / "bound_long_wave.py").string() +
                          "' --target '" + (d / "target.csv").string() + "' --face 0.14 '" +
                          (d / "exact").string() + "' '" + (d / "low").string() + "' '" +
                          (d / "free").string() + "' -o '" + (d / "out").string() + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const auto rows = csv_rows_by_first_cell(d / "out" / "bound_long_wave.csv", 13);
  ASSERT_EQ(rows.size(), 3u);
  // measured / bound (5), phase lag (6), not bound / bound (8), ratio to the measured a1 a2 (12).
  EXPECT_NEAR(std::stod(rows.at("exact")[5]), 1.0, 0.01);
  EXPECT_NEAR(std::stod(rows.at("exact")[6]), 0.0, 0.005);
  EXPECT_NEAR(std::stod(rows.at("exact")[8]), 0.0, 0.01);
  EXPECT_NEAR(std::stod(rows.at("low")[5]), 0.81, 0.02);
  EXPECT_NEAR(std::stod(rows.at("low")[12]), 1.0, 0.02);
  EXPECT_NEAR(std::stod(rows.at("free")[8]), 1.0, 0.02);
  EXPECT_TRUE(fs::exists(d / "out" / "bound_long_wave.png"));
}

// validation/wave_flume2d/irregular_long_wave.py on synthetic gauges: a sea of short waves over
// a known long wave; the gauge that carries exactly the target's bound wave reads it (ratio 1,
// no difference, correlation 1); one with a free long wave of the same RMS added, uncorrelated
// with it, reads a difference as large as the bound wave.
TEST(Plots, IrregularLongWaveScriptReadsKnownLongWaves) {
  constexpr double kPi = std::numbers::pi;
  std::string why;
  if (!plots_possible(&why)) GTEST_SKIP() << "plot checks skipped: " << why;
  const std::string python = find_plot_python();
  const fs::path src(SWELL_SOURCE_DIR);
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_plots" / "irregular_long_wave";
  fs::remove_all(d);
  fs::create_directories(d);
  const auto sea = [&](double t) {
    double e = 0;
    for (int i = 0; i < 12; ++i) e += 0.004 * std::cos(2 * kPi * (0.6 + 0.05 * i) * t + 0.7 * i);
    return e;
  };
  // Long waves at 0.05-0.2 Hz: the bound one, and a free one on other frequencies.
  const auto bound = [&](double t) {
    return 0.001 * std::cos(2 * kPi * 0.05 * t + 0.3) + 0.0007 * std::cos(2 * kPi * 0.12 * t);
  };
  const auto free = [&](double t) {
    return 0.001 * std::cos(2 * kPi * 0.08 * t + 1.1) + 0.0007 * std::cos(2 * kPi * 0.17 * t);
  };
  {
    std::ofstream tgt(d / "target.csv");
    tgt << "# synthetic\ntime [s],eta_2 [m],eta_bound_2 [m]\n";
    for (int i = 0; i <= 8000; ++i) {
      const double t = 0.01 * i;
      tgt << t << "," << sea(t) + bound(t) << "," << bound(t) << "\n";
    }
  }
  const auto run = [&](const std::string& name, double with_free) {
    fs::create_directories(d / name);
    std::ofstream g(d / name / "gauges_height.csv");
    g << "# swell gauges\ntime [s],eta_a [m]\n";
    for (int i = 0; i <= 8000; ++i) {
      const double t = 0.01 * i;
      g << t << "," << 0.4 + sea(t) + bound(t) + with_free * free(t) << "\n";
    }
  };
  run("exact", 0.0);
  run("free", 1.0);
  const std::string cmd =
      "'" + python + "' '" +
      (src / "validation" / "wave_flume2d" / "irregular_long_wave.py").string() + "' --target '" +
      (d / "target.csv").string() + "' --gauges eta_a:2 --window 10:70 '" + (d / "exact").string() +
      "' '" + (d / "free").string() + "' -o '" + (d / "out").string() + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const auto rows = csv_rows_by_first_cell(d / "out" / "irregular_long_wave.csv", 9);
  ASSERT_EQ(rows.size(), 2u);
  // measured / bound (5), difference / bound (7), correlation (8).
  EXPECT_NEAR(std::stod(rows.at("exact")[5]), 1.0, 0.03);
  EXPECT_LT(std::stod(rows.at("exact")[7]), 0.05);
  EXPECT_GT(std::stod(rows.at("exact")[8]), 0.99);
  EXPECT_NEAR(std::stod(rows.at("free")[7]), 1.0, 0.1);
  EXPECT_LT(std::stod(rows.at("free")[8]), 0.85);
  EXPECT_TRUE(fs::exists(d / "out" / "irregular_long_wave.png"));
}

}  // namespace
}  // namespace swell
