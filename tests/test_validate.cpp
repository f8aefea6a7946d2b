// The validation pipeline without running any solver: manifest errors name the file, line
// and field; `swell compare` on synthetic runs writes the metrics CSV and the report with the
// expected numbers; `swell validate` on committed results works where OpenFOAM is absent and
// reports targets; the shipped manifests load and their cases parse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/validate_command.hpp"
#include "case/reader.hpp"
#include "foam/foam.hpp"
#include "validation/validation_manifest.hpp"
#include "validation/validation_report.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_validate" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The non-comment lines of a CSV, split at commas.
std::vector<std::vector<std::string>> csv_rows(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream f(p);
  for (std::string line; std::getline(f, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

// A run folder with gauges_front.csv: front = 1 + t + amplitude sin(2 pi t) [m], every 0.01 s.
void write_run(const fs::path& dir, double amplitude) {
  std::ostringstream csv;
  csv << "# swell gauges, case synthetic\n# surge front\ntime [s],front [m]\n";
  for (int i = 0; i <= 200; ++i) {
    const double t = 0.01 * i;
    csv << t << "," << 1.0 + t + amplitude * std::sin(2 * kPi * t) << "\n";
  }
  write(dir / "gauges_front.csv", csv.str());
}

void write_reference(const fs::path& file) {
  std::ostringstream csv;
  csv << "# synthetic reference: x = 1 + t\nT,x_front,other\n";
  for (int i = 0; i <= 40; ++i) csv << 0.05 * i << "," << 1.0 + 0.05 * i << ",0\n";
  write(file, csv.str());
}

TEST(Validate, CompareWritesMetricsAndReport) {
  const fs::path d = scratch("compare");
  write_run(d / "a", 0.0);
  write_run(d / "b", 0.1);
  write_reference(d / "ref.csv");
  CompareOptions opt;
  opt.runs = {(d / "a").string(), (d / "b").string()};
  opt.labels = {"exact", "wavy"};
  opt.reference = (d / "ref.csv").string();
  opt.out_dir = (d / "out").string();
  std::ostringstream log;
  const CompareSummary s = run_compare(opt, log);
  EXPECT_EQ(s.rows, 2);  // gauge "front" matched column "x_front" by suffix
  const std::string csv = read(d / "out" / "metrics.csv");
  EXPECT_NE(csv.find("exact,,0,front,ref.csv"), std::string::npos) << csv;
  const std::string report = read(d / "out" / "report.md");
  EXPECT_NE(report.find("| front | wavy | ref.csv |"), std::string::npos) << report;
  if (!s.plots) EXPECT_NE(report.find("Plots skipped"), std::string::npos);

  // The exact run has zero error; the wavy one has RMS 0.1/sqrt(2) over two whole periods,
  // sampled at the reference times (0.05 s; 20 per period: exact for a sine).
  const auto rows = csv_rows(d / "out" / "metrics.csv");
  ASSERT_EQ(rows.size(), 3u);  // header + 2
  const auto col = std::find(rows[0].begin(), rows[0].end(), "nrmse") - rows[0].begin();
  ASSERT_LT(col, static_cast<long>(rows[0].size()));
  // Reference range over the whole window: x from 1 to 3.
  EXPECT_NEAR(std::stod(rows[1][col]), 0.0, 1e-12);
  EXPECT_NEAR(std::stod(rows[2][col]), 0.1 / std::sqrt(2.0) / 2.0, 1e-3);

  // No common gauge: a clear error.
  CompareOptions none = opt;
  none.map = {"front=missing_column"};
  EXPECT_THROW(run_compare(none, log), std::invalid_argument);
}

// A self-contained validation folder: case file, reference, committed results. `t1_extra` is
// added to the first target's map.
fs::path make_validation(const fs::path& root, const std::string& manifest_extra = "",
                         const std::string& t1_extra = "") {
  write(root / "cases" / "tiny.yaml",
        "name: tiny\ndim: 2\ndp: 0.01\ntime: {end: 0.1}\nbodies:\n"
        "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}}\n"
        "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.2, 0.2]}}}\n"
        "gauges:\n  - {name: front, kind: front}\n");
  write_reference(root / "validation" / "tiny" / "ref.csv");
  write_run(root / "validation" / "tiny" / "results" / "sph_dp0.01", 0.0);
  write_run(root / "validation" / "tiny" / "results" / "foam_dx0.01", 0.2);
  write(root / "validation" / "tiny" / "results" / "sph_dp0.01" / "run_info.yaml",
        "kind: sph\nresolution: 0.01\nwall_seconds: 12.5\nsize: 400\nend_time: 2\n");
  write(root / "validation" / "tiny" / "results" / "foam_dx0.01" / "run_info.yaml",
        "kind: openfoam\nresolution: 0.01\nwall_seconds: 30\nsize: 10000\nend_time: 2\n");
  write(root / "validation" / "tiny" / "validation.yaml",
        "title: tiny check\ncase: ../../cases/tiny.yaml\n"
        "normalisation:\n  front: {time_scale: 1, value_scale: 1, value_label: x}\n"
        "references:\n  - {name: experiment, file: ref.csv}\n"
        "gauges:\n  - {gauge: front, normalisation: front, reference: {experiment: x_front},\n"
        "     window: [0.2, 1.8], relative: true}\n"
        "targets:\n"
        "  - {gauge: front, against: experiment, metric: max_rel_error, max: 0.05, text: t1" +
            t1_extra +
            "}\n"
            "  - {gauge: front, against: openfoam, metric: max_rel_error, max: 0.05, runs: sph,\n"
            "     text: t2}\n"
            "runs:\n  sph: {resolutions: [0.01]}\n  openfoam: {cell_sizes: [0.01, 0.005]}\n" +
            manifest_extra);
  return root / "validation" / "tiny";
}

TEST(Validate, CommittedResultsWithoutOpenFoam) {
  const fs::path root = scratch("committed");
  make_validation(root);
  ValidateOptions opt;
  opt.name = "tiny";
  opt.search_root = root.string();
  opt.out_dir = (root / "out").string();
  std::ostringstream log;
  const ValidateSummary s = run_validate(opt, log);
  // sph and foam against the experiment, sph against openfoam.
  EXPECT_EQ(s.rows, 3);
  // t1: sph exact (pass), foam off by up to 0.2/1.x (fail); t2: sph vs foam (fail).
  EXPECT_EQ(s.targets_pass, 1);
  EXPECT_EQ(s.targets_fail, 2);
  // foam_dx0.005 was listed but has no results: a note, not an error.
  bool noted = false;
  for (const auto& n : s.notes) noted = noted || n.find("foam_dx0.005") != std::string::npos;
  EXPECT_TRUE(noted);
  const std::string report = read(root / "out" / "report.md");
  EXPECT_NE(report.find("| sph_dp0.01 | SPH | 0.01 | 400 |"), std::string::npos) << report;
  EXPECT_NE(report.find("| foam_dx0.01 | interFoam | 0.01 | 10000 |"), std::string::npos);
  EXPECT_NE(report.find("**fail**"), std::string::npos);
  EXPECT_TRUE(fs::exists(root / "out" / "metrics.csv"));
  // No target lists known failures: both misses are unexpected.
  EXPECT_EQ(s.targets_known_fail, 0);
  EXPECT_EQ(s.unexpected_failures.size(), 2u);
  EXPECT_TRUE(s.stale_known_failures.empty());
}

TEST(Validate, KnownFailuresAreReportedApart) {
  const fs::path root = scratch("known");
  make_validation(root, "", ", known_failures: [foam_dx0.01]");
  ValidateOptions opt;
  opt.name = "tiny";
  opt.search_root = root.string();
  opt.out_dir = (root / "out").string();
  std::ostringstream log;
  ValidateSummary s = run_validate(opt, log);
  EXPECT_EQ(s.targets_fail, 2);
  EXPECT_EQ(s.targets_known_fail, 1);           // t1, foam_dx0.01
  ASSERT_EQ(s.unexpected_failures.size(), 1u);  // t2, sph_dp0.01 against openfoam
  EXPECT_EQ(s.unexpected_failures[0].rfind("t2: sph_dp0.01 max_rel_error = ", 0), 0u)
      << s.unexpected_failures[0];
  EXPECT_TRUE(s.stale_known_failures.empty());
  EXPECT_NE(read(root / "out" / "report.md").find("**fail** (known)"), std::string::npos);

  // A listed result that meets the target: the list is out of date.
  make_validation(root, "", ", known_failures: [foam_dx0.01, sph_dp0.01]");
  s = run_validate(opt, log);
  ASSERT_EQ(s.stale_known_failures.size(), 1u);
  EXPECT_EQ(s.stale_known_failures[0].rfind("t1: sph_dp0.01 ", 0), 0u) << s.stale_known_failures[0];

  // A label that is no result of the runs section is a manifest error.
  const fs::path dir = make_validation(root, "", ", known_failures: [sph_dp0.02]");
  try {
    load_manifest((dir / "validation.yaml").string());
    FAIL() << "expected a ManifestError";
  } catch (const ManifestError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "targets[0].known_failures[0]: 'sph_dp0.02' is not a result of the runs "
                  "section (expected one of: sph_dp0.01, foam_dx0.01, foam_dx0.005)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Validate, ManifestErrorsNameFileLineAndField) {
  const fs::path root = scratch("errors");
  struct Case {
    std::string extra, expect;
  };
  // Each appends a faulty key; the message must name it.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"unknown_key: 1\n", "unknown_key: unknown key"},
      {"end_time: soon\n", "end_time: expected a number"},
  };
  for (const auto& [extra, expect] : bad) {
    const fs::path dir = make_validation(root, extra);
    try {
      load_manifest((dir / "validation.yaml").string());
      FAIL() << "expected a ManifestError for " << extra;
    } catch (const ManifestError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("validation.yaml:"), std::string::npos) << msg;
      EXPECT_NE(msg.find(expect), std::string::npos) << msg;
    }
  }
  // A wrong field inside a list item: the path is given with its index, and the line.
  write(root / "bad" / "ref.csv", "t,x\n0,1\n");
  write(root / "bad" / "validation.yaml",
        "case: ../validation/tiny/../../cases/tiny.yaml\n"
        "normalisation:\n  n: {time_scale: 1, value_scale: 1}\n"
        "references:\n  - {name: e, file: ref.csv}\n"
        "gauges:\n  - {gauge: g, normalisation: n, window: [2, 1]}\n");
  try {
    load_manifest((root / "bad" / "validation.yaml").string());
    FAIL();
  } catch (const ManifestError& e) {
    EXPECT_NE(std::string(e.what()).find("validation.yaml:7: gauges[0].window: expected t1 > t0"),
              std::string::npos)
        << e.what();
  }
  // Load metrics: a filter needs a peak window to look in, and a positive width.
  for (const auto& [gauge, expect] : std::vector<std::pair<std::string, std::string>>{
           {"{gauge: g, normalisation: n, filter: 0.01}", "gauges[0].filter: needs peak_window"},
           {"{gauge: g, normalisation: n, peak_window: [0, 1], filter: 0}",
            "gauges[0].filter: expected a width > 0"},
           {"{gauge: g, normalisation: n, impulse_window: [1, 0]}",
            "gauges[0].impulse_window: expected t1 > t0"}}) {
    write(root / "bad" / "validation.yaml",
          "case: ../validation/tiny/../../cases/tiny.yaml\n"
          "normalisation:\n  n: {time_scale: 1, value_scale: 1}\n"
          "references:\n  - {name: e, file: ref.csv}\n"
          "gauges:\n  - " +
              gauge + "\n");
    try {
      load_manifest((root / "bad" / "validation.yaml").string());
      ADD_FAILURE() << gauge << " was accepted";
    } catch (const ManifestError& e) {
      EXPECT_NE(std::string(e.what()).find("validation.yaml:7: " + expect), std::string::npos)
          << e.what();
    }
  }
  write(root / "bad" / "validation.yaml",
        "case: ../cases/tiny.yaml\nnormalisation:\n  n: {time_scale: 1, value_scale: 1}\n"
        "references:\n  - {name: e, file: missing.csv}\ngauges: []\n");
  try {
    load_manifest((root / "bad" / "validation.yaml").string());
    FAIL();
  } catch (const ManifestError& e) {
    EXPECT_NE(std::string(e.what()).find("references[0].file: the reference file"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(find_manifest("no_such_case", root.string()), ManifestError);
}

TEST(Validate, ManifestCaseOverridesDpEndTimeAndGauges) {
  const fs::path root = scratch("override");
  const fs::path dir = make_validation(
      root, "extra_gauges:\n  - {name: H_x, kind: height, at: [0.1, 0.0]}\nend_time: 0.05\n");
  const Manifest m = load_manifest((dir / "validation.yaml").string());
  const CaseSpec spec = load_manifest_case(m, 0.005);
  EXPECT_DOUBLE_EQ(spec.dp, 0.005);
  EXPECT_DOUBLE_EQ(spec.t_end, 0.05);
  ASSERT_EQ(spec.gauges.size(), 2u);
  EXPECT_EQ(spec.gauges[1].name, "H_x");
  EXPECT_EQ(spec.bodies.size(), 2u);
  EXPECT_EQ(sph_label(0.00142875), "sph_dp0.00142875");
  EXPECT_EQ(foam_label(0.005), "foam_dx0.005");
  // `swell validate --set`: the command-line edits apply first, then the manifest's dp, end time
  // and extra gauges (also without any of those, and an edit's error names the edit).
  Manifest edited = m;
  edited.case_sets = {"physics.boundary.model=mdbc", "dp=0.02", "time.end=3"};
  const CaseSpec with_sets = load_manifest_case(edited, 0.005);
  EXPECT_EQ(with_sets.boundary, BoundaryType::Mdbc);
  EXPECT_DOUBLE_EQ(with_sets.dp, 0.005);    // the manifest's dp wins over the edit
  EXPECT_DOUBLE_EQ(with_sets.t_end, 0.05);  // and its end time
  ASSERT_EQ(with_sets.gauges.size(), 2u);
  Manifest plain = m;
  plain.end_time.reset();
  plain.extra_gauges_yaml.clear();
  plain.case_sets = {"physics.boundary.model=mdbc"};
  EXPECT_EQ(load_manifest_case(plain).boundary, BoundaryType::Mdbc);
  plain.case_sets = {"physics.boundary"};
  EXPECT_THROW(load_manifest_case(plain), CaseError);
}

TEST(Validate, ShippedManifestsLoadAndTheirCasesParse) {
  for (const char* name : {"martin_moyce", "lobovsky2d", "foam_dambreak2d", "spheric_test2"}) {
    SCOPED_TRACE(name);
    const Manifest m = load_manifest(find_manifest(name, SWELL_SOURCE_DIR));
    const CaseSpec spec = load_manifest_case(m);
    // Every compared gauge exists in the case (or the manifest's extra gauges).
    for (const auto& g : m.gauges) {
      bool found = false;
      for (const auto& cg : spec.gauges) found = found || cg.name == g.gauge;
      EXPECT_TRUE(found) << g.gauge;
      for (const auto& [ref, column] : g.columns)
        EXPECT_GE(read_series_table(m.reference(ref)->file).find(column), 0) << column;
    }
    EXPECT_FALSE(m.sph_resolutions.empty());
  }
}

// The CI check: a coarse SPH run and a coarse interFoam run of the damBreak tutorial
// geometry, shortened, through the whole pipeline; both fronts agree within a loose tolerance.
// Skipped where OpenFOAM is not installed.
TEST(Validate, EndToEndFoamDambreakCoarse) {
  std::string why;
  if (!openfoam_available(&why)) GTEST_SKIP() << "OpenFOAM not available: " << why;
  ValidateOptions opt;
  opt.name = "foam_dambreak2d";
  opt.search_root = SWELL_SOURCE_DIR;
  opt.out_dir = scratch("foam_dambreak2d_e2e").string();
  opt.run_sph = opt.run_foam = true;
  opt.resolutions = {0.008};
  opt.cell_sizes = {0.008};
  opt.end_time = 0.25;
  opt.progress = false;
  std::ostringstream log;
  const ValidateSummary s = run_validate(opt, log);
  EXPECT_TRUE(s.notes.empty() || s.notes.front().find("failed") == std::string::npos) << log.str();
  const auto rows = csv_rows(fs::path(opt.out_dir) / "metrics.csv");
  ASSERT_GE(rows.size(), 2u) << log.str();
  const auto& h = rows[0];
  const long run = std::find(h.begin(), h.end(), "run") - h.begin();
  const long gauge = std::find(h.begin(), h.end(), "gauge") - h.begin();
  const long ref = std::find(h.begin(), h.end(), "reference") - h.begin();
  const long max_rel = std::find(h.begin(), h.end(), "max_rel_error") - h.begin();
  bool found = false;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (rows[i][run] != "sph_dp0.008" || rows[i][gauge] != "front" || rows[i][ref] != "openfoam")
      continue;
    found = true;
    EXPECT_LT(std::stod(rows[i][max_rel]), 0.15) << "SPH and interFoam fronts differ";
  }
  EXPECT_TRUE(found) << log.str();
}

// Every shipped validation case, from its committed results: each target is met by each
// result, or the result is listed in the target's known_failures (and a listed result does miss
// it). A committed result that gets worse, or better, than its manifest says fails here.
TEST(Validate, ShippedResultsMeetTheirTargetsOrAreKnownFailures) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SWELL_SOURCE_DIR) / "validation")) {
    const fs::path manifest = entry.path() / "validation.yaml";
    if (!fs::is_regular_file(manifest)) continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const Manifest m = load_manifest(manifest.string());
    if (!fs::is_directory(m.results_dir)) continue;
    ValidateOptions opt;
    opt.name = name;
    opt.search_root = SWELL_SOURCE_DIR;
    opt.out_dir = scratch("shipped_" + name).string();
    std::ostringstream log;
    const ValidateSummary s = run_validate(opt, log);
    EXPECT_GE(s.rows, 2);
    EXPECT_GE(s.targets_pass + s.targets_fail, 1);
    EXPECT_TRUE(fs::exists(fs::path(opt.out_dir) / "report.md"));
    std::string unexpected, stale;
    for (const auto& u : s.unexpected_failures) unexpected += "\n  " + u;
    for (const auto& k : s.stale_known_failures) stale += "\n  " + k;
    EXPECT_TRUE(unexpected.empty()) << "committed results miss targets that " << m.file
                                    << " does not list in known_failures:" << unexpected;
    EXPECT_TRUE(stale.empty()) << "known_failures of " << m.file << " out of date:" << stale;
    ++checked;
  }
  EXPECT_GE(checked, 4);  // martin_moyce, lobovsky2d, foam_dambreak2d, spheric_test2
}

}  // namespace
}  // namespace swell
