// Provenance in every output (issue #17): each command that writes a folder or a result file,
// run as the real `swell` on a tiny input, says how it was made (version, commit, compiler,
// build flags, command line, threads, ranks, date, host, CPU); the HDF5 run file's datasets
// carry units; each .vtp carries its time and the body names.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "case/setup.hpp"
#include "child_process.hpp"
#include "io/hdf5_file.hpp"
#include "io/provenance.hpp"
#include "io/run_info.hpp"
#include "validation/validation_manifest.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

const std::string kSwell = std::string(SWELL_BINARY_DIR) + "/swell";

fs::path fresh_root(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("swell_test_provenance_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs `swell args...`; returns the exit code, stderr in root/stderr.txt.
int swell(const std::vector<std::string>& args, const fs::path& root) {
  std::vector<std::string> all = {kSwell};
  all.insert(all.end(), args.begin(), args.end());
  test::ChildOptions o;
  o.err = (root / "stderr.txt").string();
  return test::wait_exit(test::spawn(all, o));
}
#define SWELL_OK(args, root) ASSERT_EQ(swell(args, root), 0) << read_text((root) / "stderr.txt")

// This checkout is a git work tree, so the build must know its commit.
bool built_from_git() {
  return fs::exists(fs::path(SWELL_SOURCE_DIR) / ".git");
}

// Every field present and meaningful; `command` names the subcommand.
void expect_complete(const Provenance& p, const std::string& subcommand, int threads = 0) {
  for (const auto& [k, v] : p.fields()) EXPECT_FALSE(v.empty()) << "field " << k << " is empty";
  EXPECT_TRUE(p.recovered.empty());
  EXPECT_EQ(p.version, capture_provenance().version);
  if (built_from_git())
    EXPECT_TRUE(std::regex_match(p.commit, std::regex("[0-9a-f]{7,40}(-dirty)?"))) << p.commit;
  else
    EXPECT_TRUE(p.commit == "unknown" ||
                std::regex_match(p.commit, std::regex("[0-9a-f]{7,40}.*")));
  EXPECT_NE(p.build.find("Release"), std::string::npos) << p.build;
  EXPECT_NE(p.build.find("-march="), std::string::npos) << p.build;
  EXPECT_NE(p.command.find(kSwell + " " + subcommand), std::string::npos) << p.command;
  EXPECT_GE(p.threads, 1);
  if (threads > 0) EXPECT_EQ(p.threads, threads);
  EXPECT_EQ(p.ranks, 1);
  EXPECT_TRUE(
      std::regex_match(p.date, std::regex("20[0-9]{2}-[01][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:"
                                          "[0-6][0-9]Z")))
      << p.date;
  EXPECT_NE(p.cpu, "unknown");
}

// The provenance of a run_info.yaml-style file (one entry expected unless `entries`).
std::vector<Provenance> provenance_of(const fs::path& dir, std::size_t entries = 1) {
  const RunInfo info = read_run_info(dir.string());
  EXPECT_EQ(info.provenance.size(), entries) << dir;
  return info.provenance;
}

// Sets the field `key` of `p` from its text (unknown keys are ignored).
void set_field(Provenance& p, const std::string& k, const std::string& v) {
  if (k == "version") p.version = v;
  if (k == "commit") p.commit = v;
  if (k == "compiler") p.compiler = v;
  if (k == "build") p.build = v;
  if (k == "command") p.command = v;
  if (k == "threads") p.threads = std::stoi(v);
  if (k == "ranks") p.ranks = std::stoi(v);
  if (k == "date") p.date = v;
  if (k == "host") p.host = v;
  if (k == "cpu") p.cpu = v;
}

// '# key: value' provenance lines at the top of a CSV file, as a Provenance.
Provenance provenance_of_csv(const fs::path& csv) {
  std::ifstream in(csv);
  Provenance p;
  p.threads = 0;
  p.ranks = 0;
  const std::regex line("# ([a-z]+): +(.*)");
  for (std::string l; std::getline(in, l) && l.starts_with("#");) {
    std::smatch m;
    if (!std::regex_match(l, m, line)) continue;
    set_field(p, m[1], m[2]);
  }
  return p;
}

// A 2D tank with a box structure and water `fill: below` (~600 particles; under a second).
std::string tiny_case(const fs::path& dir) {
  const std::string text =
      "name: tiny\ndim: 2\ndp: 0.01\ntime: {end: 0.02}\nbodies:\n"
      "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.4, 0.3]}}, "
      "layers: 3, open: [ymax]}\n"
      "  - {name: block, kind: boundary, walls: outside, shape: {box: {min: [0.3, 0], max: "
      "[0.35, 0.05]}}}\n"
      "  - {name: water, kind: fluid, fill: {below: 0.1, inside: tank}}\n"
      "gauges:\n  - {name: front, kind: front}\n  - {name: F, kind: force, body: block}\n"
      "output: {every: 0.01, vtk: true, hdf5: true}\n";
  const fs::path p = dir / "tiny.yaml";
  std::ofstream(p) << text;
  return p.string();
}

// The string attribute `name` of an open object, "" when absent.
std::string string_attr(hid_t obj, const char* name) {
  if (H5Aexists(obj, name) <= 0) return "";
  const hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  const hid_t t = H5Aget_type(a);
  std::string v;
  if (H5Tis_variable_str(t) > 0) {
    char* s = nullptr;
    const hid_t mem = H5Tget_native_type(t, H5T_DIR_ASCEND);
    if (H5Aread(a, mem, &s) >= 0 && s) v = s;
    H5free_memory(s);
    H5Tclose(mem);
  }
  H5Tclose(t);
  H5Aclose(a);
  return v;
}

// Every dataset below `loc` (links followed, external ones too): full path -> units.
void collect_units(hid_t loc, const std::string& path, std::map<std::string, std::string>& out) {
  H5G_info_t info;
  ASSERT_GE(H5Gget_info(loc, &info), 0);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[256];
    H5Lget_name_by_idx(loc, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT);
    const hid_t obj = H5Oopen(loc, name, H5P_DEFAULT);
    ASSERT_GE(obj, 0) << path << "/" << name;
    H5O_info_t oi;
    H5Oget_info(obj, &oi);
    const std::string full = path + "/" + name;
    if (oi.type == H5O_TYPE_GROUP) collect_units(obj, full, out);
    if (oi.type == H5O_TYPE_DATASET) out[full] = string_attr(obj, "units");
    H5Oclose(obj);
  }
}

class Provenance17 : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fresh_root("run");
    case_ = tiny_case(root_);
    out_ = root_ / "out";
    rc_ = swell({"run", case_, "-o", out_.string(), "-q", "-t", "1"}, root_);
  }
  void SetUp() override { ASSERT_EQ(rc_, 0) << read_text(root_ / "stderr.txt"); }
  static fs::path root_, out_;
  static std::string case_;
  static int rc_;
};
fs::path Provenance17::root_, Provenance17::out_;
std::string Provenance17::case_;
int Provenance17::rc_ = -1;

TEST_F(Provenance17, RunWritesItToRunInfoSummaryAndHdf5) {
  const auto p = provenance_of(out_);
  ASSERT_EQ(p.size(), 1u);
  expect_complete(p[0], "run", 1);
  EXPECT_NE(p[0].command.find(case_), std::string::npos) << p[0].command;
  const RunInfo info = read_run_info(out_.string());
  EXPECT_EQ(info.kind, "sph");
  EXPECT_DOUBLE_EQ(info.resolution, 0.01);
  EXPECT_GT(info.size, 0);
  EXPECT_NEAR(info.end_time, 0.02, 0.01);
  EXPECT_FALSE(info.date.empty());

  const std::string summary = read_text(out_ / "run_summary.txt");
  for (const auto& [k, v] : p[0].fields())
    EXPECT_NE(summary.find("    " + k + ":"), std::string::npos) << k << "\n" << summary;
  EXPECT_NE(summary.find(p[0].commit), std::string::npos) << summary;

  for (const fs::path& h5 : {out_ / "tiny.h5", out_ / "snapshots" / "tiny_0000000000.h5"}) {
    const RunMetadata m = read_metadata(h5.string());
    expect_complete(m.provenance, "run", 1);
    EXPECT_EQ(m.provenance.commit, p[0].commit) << h5;
  }
}

TEST_F(Provenance17, EveryDatasetOfTheRunFileHasUnits) {
  const hid_t f = H5Fopen((out_ / "tiny.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  std::map<std::string, std::string> units;
  collect_units(f, "", units);
  // case_text and, per snapshot, pos vel rho p mass type body id.
  ASSERT_GE(units.size(), 1u + 3 * 8) << units.size();
  for (const auto& [set, u] : units) EXPECT_FALSE(u.empty()) << set;
  // 2D: mass is per metre of depth; pressure in Pa, positions in m.
  const std::string snap = "/particles/0000000000";
  EXPECT_EQ(units[snap + "/mass"], "kg/m");
  EXPECT_EQ(units[snap + "/p"], "Pa");
  EXPECT_EQ(units[snap + "/pos"], "m");
  EXPECT_EQ(units[snap + "/vel"], "m/s");
  EXPECT_EQ(units[snap + "/rho"], "kg/m^3");
  EXPECT_EQ(units[snap + "/id"], "1");
  EXPECT_EQ(units["/metadata/case_text"], "1");
  H5Fclose(f);
}

TEST_F(Provenance17, EachVtpHoldsItsTimeAndBodyNames) {
  // The .pvd's times, in order, against each file's TimeValue.
  const std::string pvd = read_text(out_ / "tiny.pvd");
  const std::regex entry("timestep=\"([^\"]+)\"[^>]*file=\"([^\"]+)\"");
  int files = 0;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), entry); it != std::sregex_iterator();
       ++it, ++files) {
    const double t = std::stod((*it)[1]);
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName((out_ / (*it)[2].str()).c_str());
    reader->Update();
    vtkPolyData* poly = reader->GetOutput();
    auto* tv = vtkDoubleArray::SafeDownCast(poly->GetFieldData()->GetAbstractArray("TimeValue"));
    ASSERT_NE(tv, nullptr) << (*it)[2];
    ASSERT_EQ(tv->GetNumberOfTuples(), 1);
    EXPECT_NEAR(tv->GetValue(0), t, 1e-9 * std::max(1.0, t));
    auto* names =
        vtkStringArray::SafeDownCast(poly->GetFieldData()->GetAbstractArray("body_names"));
    ASSERT_NE(names, nullptr);
    ASSERT_EQ(names->GetNumberOfValues(), 3);
    EXPECT_EQ(names->GetValue(0), "tank");
    EXPECT_EQ(names->GetValue(1), "block");
    EXPECT_EQ(names->GetValue(2), "water");
    auto* per_point =
        vtkStringArray::SafeDownCast(poly->GetPointData()->GetAbstractArray("body_name"));
    ASSERT_NE(per_point, nullptr);
    auto* body = poly->GetPointData()->GetArray("body");
    ASSERT_NE(body, nullptr);
    for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
      ASSERT_EQ(per_point->GetValue(i),
                names->GetValue(static_cast<vtkIdType>(body->GetTuple1(i))));
  }
  EXPECT_GE(files, 2);
}

TEST_F(Provenance17, RestartAddsAnEntry) {
  const fs::path out = root_ / "restarted";
  fs::create_directories(out);
  fs::copy(out_, out, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  fs::remove(out / ".swell.lock");
  // Extend the run: time.end is not part of the case identity.
  const fs::path longer = root_ / "longer" / "tiny.yaml";
  fs::create_directories(longer.parent_path());
  std::string text = read_text(case_);
  text.replace(text.find("end: 0.02"), 9, "end: 0.03");
  std::ofstream(longer) << text;
  SWELL_OK(std::vector<std::string>(
               {"run", longer.string(), "--restart", out.string(), "-q", "-t", "1"}),
           root_);
  const auto p = provenance_of(out, 2);
  ASSERT_EQ(p.size(), 2u);
  expect_complete(p[0], "run", 1);
  expect_complete(p[1], "run", 1);
  EXPECT_NE(p[1].command.find("--restart"), std::string::npos);
  EXPECT_EQ(p[0].command.find("--restart"), std::string::npos);
  EXPECT_NE(read_text(out / "run_summary.txt").find("made by (this restart"), std::string::npos);
}

TEST_F(Provenance17, ProbeCompareFillFoamWriteIt) {
  const fs::path csv = root_ / "probe.csv";
  SWELL_OK(
      std::vector<std::string>({"probe", out_.string(), "--at", "0.05,0.02", "-o", csv.string()}),
      root_);
  expect_complete(provenance_of_csv(csv), "probe");

  const fs::path cmp = root_ / "compare";
  SWELL_OK(std::vector<std::string>(
               {"compare", out_.string(), "--reference", out_.string(), "-o", cmp.string()}),
           root_);
  expect_complete(provenance_of(cmp).at(0), "compare");
  EXPECT_NE(read_text(cmp / "report.md").find("## How this report was made"), std::string::npos);

  const fs::path fill = root_ / "fill";
  SWELL_OK(std::vector<std::string>({"fill", case_, "-o", fill.string(), "-t", "1"}), root_);
  const YAML::Node info = YAML::LoadFile((fill / "fill_info.yaml").string());
  ASSERT_TRUE(info["provenance"] && info["provenance"].IsSequence());
  ASSERT_EQ(info["provenance"].size(), 1u);
  Provenance fp;
  for (const auto& kv : info["provenance"][0]) {
    set_field(fp, kv.first.as<std::string>(), kv.second.as<std::string>());
  }
  expect_complete(fp, "fill", 1);

  const fs::path foam = root_ / "foam";
  SWELL_OK(std::vector<std::string>({"foam", case_, "-o", foam.string()}), root_);
  expect_complete(provenance_of(foam).at(0), "foam");
  EXPECT_EQ(read_run_info(foam.string()).kind, "openfoam");
}

TEST(Provenance, VersionNamesTheCommitAndBuild) {
  const fs::path root = fresh_root("version");
  const std::string cmd = kSwell + " --version > " + (root / "v.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string v = read_text(root / "v.txt");
  const Provenance p = capture_provenance();
  EXPECT_EQ(v.rfind("swell " + p.version + " (commit ", 0), 0u) << v;
  if (built_from_git())
    EXPECT_TRUE(std::regex_search(v, std::regex("commit [0-9a-f]{7,40}(-dirty)?;"))) << v;
  EXPECT_NE(v.find("-march="), std::string::npos) << v;
}

TEST(Provenance, WavesCommandsWriteItInTheirCsv) {
  const fs::path root = fresh_root("waves");
  // A 1 s regular wave sampled at 20 Hz for 40 s, and a paddle record in phase with it.
  const fs::path in = root / "gauges.csv";
  {
    std::ofstream f(in);
    f << "time [s],H1 [m],paddle [m]\n";
    for (int i = 0; i <= 800; ++i) {
      const double t = 0.05 * i;
      f << t << "," << 0.02 * std::cos(2 * M_PI * t) << "," << 0.01 * std::sin(2 * M_PI * t)
        << "\n";
    }
  }
  const fs::path a = root / "analyse.csv", p = root / "predict.csv", g = root / "goda.csv";
  SWELL_OK(std::vector<std::string>(
               {"waves", "analyse", in.string(), "--gauge", "H1", "--csv", a.string()}),
           root);
  expect_complete(provenance_of_csv(a), "waves analyse");
  SWELL_OK(std::vector<std::string>({"waves", "predict", in.string(), "--paddle", "paddle",
                                     "--depth", "0.5", "--at", "1.0", "--csv", p.string()}),
           root);
  expect_complete(provenance_of_csv(p), "waves predict");
  SWELL_OK(std::vector<std::string>({"waves", "goda", "1", "8", "10", "--csv", g.string()}), root);
  expect_complete(provenance_of_csv(g), "waves goda");
}

TEST(Provenance, BenchAndValidateWriteIt) {
  const fs::path root = fresh_root("bench");
  const fs::path bench = root / "bench";
  SWELL_OK(std::vector<std::string>({"bench", "--sweep", "--sweep-dp", "0.06", "--sweep-steps", "2",
                                     "--repeats", "1", "--threads", "1", "-o", bench.string()}),
           root);
  expect_complete(provenance_of(bench).at(0), "bench");

  // Committed results only (no run): the report and its folder say how they were made, and
  // the runs table says how each committed result was.
  const fs::path val = root / "validate";
  SWELL_OK(std::vector<std::string>({"validate",
                                     std::string(SWELL_SOURCE_DIR) + "/validation/martin_moyce",
                                     "-o", val.string()}),
           root);
  expect_complete(provenance_of(val).at(0), "validate");
  const std::string report = read_text(val / "report.md");
  EXPECT_NE(report.find("## How this report was made"), std::string::npos);
  EXPECT_NE(report.find("| made by |"), std::string::npos);
  EXPECT_EQ(report.find("| not recorded |"), std::string::npos) << report;
  EXPECT_NE(report.find("| recovered from git history on "), std::string::npos) << report;
}

TEST(Provenance, CommittedValidationResultsSayHowTheyWereMade) {
  // Every committed result folder has a run_info.yaml (or run_summary.txt) with provenance:
  // written by the command, or recovered from git history and marked so.
  int folders = 0;
  for (const auto& e :
       fs::recursive_directory_iterator(fs::path(SWELL_SOURCE_DIR) / "validation")) {
    if (!e.is_regular_file() || e.path().filename() != "run_info.yaml") continue;
    ++folders;
    const RunInfo info = read_run_info(e.path().parent_path().string());
    ASSERT_FALSE(info.provenance.empty()) << e.path();
    EXPECT_FALSE(info.date.empty()) << e.path();
    for (const Provenance& p : info.provenance) {
      if (!p.recovered.empty()) {
        EXPECT_TRUE(p.command.empty()) << e.path() << ": a recovered entry invents no command";
        EXPECT_TRUE(std::regex_search(p.recovered, std::regex("[0-9a-f]{7,40}"))) << e.path();
      } else {
        EXPECT_FALSE(p.commit.empty()) << e.path();
        EXPECT_FALSE(p.command.empty()) << e.path();
      }
    }
  }
  EXPECT_GE(folders, 15);
}

// The particle counts a committed SPH result records (run_info.yaml: size, and the fluid +
// boundary split of its note) are those its case makes at its dp today: a result whose case or
// fill changed since, or a count written by hand, fails here (SPHERIC Test 2's manifest once
// said 61k + 116k for the run's 82,350 + 94,380).
TEST(Provenance, CommittedSphResultsMatchTheirCaseCounts) {
  int checked = 0;
  for (const auto& m : fs::directory_iterator(fs::path(SWELL_SOURCE_DIR) / "validation")) {
    const fs::path manifest = m.path() / "validation.yaml";
    if (!fs::exists(manifest) || !fs::is_directory(m.path() / "results")) continue;
    const Manifest man = load_manifest(manifest.string());
    for (const auto& r : fs::directory_iterator(m.path() / "results")) {
      const RunInfo info = read_run_info(r.path().string());
      if (info.kind != "sph" || !(info.resolution > 0.0)) continue;
      const CaseSpec spec = load_manifest_case(man, info.resolution);
      std::size_t fluid = 0, boundary = 0;
      if (spec.dim == 2) {
        for (const auto& b : setup_case<2>(spec).bodies)
          (b.fluid ? fluid : boundary) += b.particles;
      } else {
        for (const auto& b : setup_case<3>(spec).bodies)
          (b.fluid ? fluid : boundary) += b.particles;
      }
      EXPECT_EQ(static_cast<std::size_t>(info.size), fluid + boundary) << r.path();
      EXPECT_EQ(info.note.rfind(std::to_string(fluid) + " fluid + " + std::to_string(boundary) +
                                    " boundary particles",
                                0),
                0u)
          << r.path() << ": " << info.note;
      ++checked;
    }
  }
  EXPECT_GE(checked, 8);
}

}  // namespace
}  // namespace swell
