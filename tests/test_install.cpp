// Swell installed like a tool (issue #17): `cmake --install` into a temporary prefix, the
// prefix moved elsewhere, and the installed `swell` run from another working directory with
// SWELL_HOME unset: `swell validate martin_moyce` finds its manifest, reference data and
// committed results under share/swell and writes its report into the user's folder, nothing
// into the installed tree; a wrong SWELL_HOME names the places tried. Also the run log
// (OUTDIR/run.log, stdout flushed at every line: a redirected, killed run keeps its header)
// and scripts/setup's refusal to remove packages (ParaView's Python), with fake apt tools.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "io/resources.hpp"
#include "tests/child_process.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

const fs::path kBuild = SWELL_BINARY_DIR;
const fs::path kSource = SWELL_SOURCE_DIR;

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

struct Result {
  int rc;
  std::string out, err;
};

// Runs `args` (absolute paths) in `cwd` with SWELL_HOME removed from the environment unless
// `env` sets it; stdout and stderr are returned.
Result run(const std::vector<std::string>& args, const fs::path& cwd,
           std::vector<std::string> env = {}) {
  test::ChildOptions o;
  o.cwd = cwd.string();
  o.env = std::move(env);
  if (o.env.empty()) o.unset = {"SWELL_HOME", "SWELL_PLOT_SCRIPT"};
  o.out = (cwd / "stdout.txt").string();
  o.err = (cwd / "stderr.txt").string();
  const int rc = test::wait_exit(test::spawn(args, o));
  return {rc, read_text(o.out), read_text(o.err)};
}

// Every file below `dir` with its size and modification time.
std::map<std::string, std::pair<std::uintmax_t, fs::file_time_type>> listing(const fs::path& dir) {
  std::map<std::string, std::pair<std::uintmax_t, fs::file_time_type>> m;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    m[fs::relative(e.path(), dir).string()] = {e.is_regular_file() ? e.file_size() : 0,
                                               e.last_write_time()};
  return m;
}

// One installation for the suite: cmake --install into a temporary prefix, then the prefix is
// renamed, so the installed programs can only find their files relative to themselves.
class Install : public ::testing::Test {
 protected:
  static fs::path root, prefix;
  static std::string install_log;
  static int install_rc;

  static void SetUpTestSuite() {
    // One folder per process: ctest runs each test in its own process, maybe in parallel.
    root = fs::temp_directory_path() / ("swell_test_install_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "work");
    const fs::path staged = root / "staged";
    const std::string cmd = "cmake --install '" + kBuild.string() + "' --prefix '" +
                            staged.string() + "' > '" + (root / "install.log").string() + "' 2>&1";
    install_rc = std::system(cmd.c_str());
    install_log = read_text(root / "install.log");
    prefix = root / "moved prefix";  // a space too: paths are quoted where they go to a shell
    if (install_rc == 0) fs::rename(staged, prefix);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
  void SetUp() override { ASSERT_EQ(install_rc, 0) << install_log; }

  static fs::path swell() { return prefix / "bin" / "swell"; }
  static fs::path data() { return prefix / "share" / "swell"; }
};
fs::path Install::root, Install::prefix;
std::string Install::install_log;
int Install::install_rc = -1;

TEST_F(Install, LayoutHoldsTheProgramsAndTheirFiles) {
  for (const char* f : {"bin/swell", "bin/swell_bench_run"}) {
    struct stat st {};
    ASSERT_EQ(::stat((prefix / f).c_str(), &st), 0) << f;
    EXPECT_TRUE(st.st_mode & S_IXUSR) << f;
  }
  for (const char* f :
       {"cases/dambreak2d.yaml", "cases/geometry/flume_beach.stl", "cases/geometry/caisson.stl",
        "validation/martin_moyce/validation.yaml",
        "validation/martin_moyce/martin_moyce_1952_residual_height.csv",
        "validation/reference/martin_moyce_1952_front.csv",
        "validation/martin_moyce/results/sph_dp0.0028575/gauges_front.csv",
        "validation/eagre/eagre_202002_paddle_probes.csv", "validation/plot_validation.py",
        "validation/synolakis/runup_table.py", "bench/cases/b2d.yaml", "bench/plot_scaling.py"})
    EXPECT_TRUE(fs::is_regular_file(data() / f)) << f;
  EXPECT_TRUE(fs::is_regular_file(prefix / "share" / "doc" / "swell" / "README.md"));
  // Sources stay in the checkout.
  for (const auto& e : fs::recursive_directory_iterator(data())) {
    const std::string ext = e.path().extension().string();
    EXPECT_TRUE(ext != ".cpp" && ext != ".hpp") << e.path();
  }
}

TEST_F(Install, ValidateFromAnotherFolderUsesTheInstalledData) {
  const fs::path work = root / "work" / "validate";
  fs::create_directories(work);
  const auto before = listing(prefix);
  const Result r = run({swell().string(), "validate", "martin_moyce"}, work);
  ASSERT_EQ(r.rc, 0) << r.err;
  const fs::path out = work / "out" / "validate" / "martin_moyce";
  ASSERT_TRUE(fs::is_regular_file(out / "report.md")) << r.err;
  EXPECT_TRUE(fs::is_regular_file(out / "metrics.csv"));
  const std::string report = read_text(out / "report.md");
  // The manifest it read is the installed one (the prefix was moved after the install, so it
  // was found from the executable's own path, not from the source tree).
  const std::string manifest =
      (data() / "validation" / "martin_moyce" / "validation.yaml").string();
  EXPECT_TRUE(contains(report, manifest)) << report.substr(0, 2000);
  EXPECT_FALSE(contains(report, kSource.string() + "/validation")) << report.substr(0, 2000);
  // The committed results were used: both SPH and both interFoam resolutions are reported.
  for (const char* label : {"sph_dp0.0028575", "sph_dp0.00142875", "foam_dx0.0028575"})
    EXPECT_TRUE(contains(report, label)) << label;
  EXPECT_EQ(listing(prefix), before) << "swell validate wrote into the installed tree";
}

TEST_F(Install, WrongSwellHomeNamesThePlacesTried) {
  const fs::path work = root / "work" / "home";
  fs::create_directories(work);
  const Result r =
      run({swell().string(), "validate", "martin_moyce"}, work, {"SWELL_HOME=/nonexistent"});
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "no validation manifest for 'martin_moyce'")) << r.err;
  EXPECT_TRUE(contains(r.err, "/nonexistent/validation/martin_moyce/validation.yaml (SWELL_HOME)"))
      << r.err;
  EXPECT_TRUE(contains(r.err, "martin_moyce/validation.yaml")) << r.err;  // the name as a path
  EXPECT_TRUE(contains(r.err, "SWELL_HOME is set, so no other place was searched")) << r.err;
  EXPECT_FALSE(fs::exists(work / "out"));
  // The same for the benchmark's cases.
  const Result b = run({swell().string(), "bench", "b2d", "--threads", "1", "--repeats", "1"}, work,
                       {"SWELL_HOME=/nonexistent"});
  EXPECT_EQ(b.rc, 2) << b.err;
  EXPECT_TRUE(contains(b.err, "/nonexistent/bench/cases/b2d.yaml (SWELL_HOME)")) << b.err;
  // SWELL_HOME pointing at a checkout works like the install prefix.
  const Result ok = run({swell().string(), "validate", "martin_moyce", "-o", "rep"}, work,
                        {"SWELL_HOME=" + kSource.string()});
  EXPECT_EQ(ok.rc, 0) << ok.err;
  EXPECT_TRUE(contains(read_text(work / "rep" / "report.md"),
                       (kSource / "validation" / "martin_moyce" / "validation.yaml").string()));
}

TEST_F(Install, SaveResultsIntoTheInstalledTreeIsRefused) {
  const fs::path work = root / "work" / "save";
  fs::create_directories(work);
  const auto before = listing(prefix);
  const Result r = run({swell().string(), "validate", "martin_moyce", "--save-results"}, work);
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "part of the installed share/swell")) << r.err;
  EXPECT_EQ(listing(prefix), before);
}

TEST_F(Install, InstalledCaseFindsItsMeshes) {
  // wave_flume2d names geometry/flume_beach.stl and geometry/caisson.stl relative to itself.
  const fs::path work = root / "work" / "fill";
  fs::create_directories(work);
  const Result r = run({swell().string(), "fill", (data() / "cases" / "wave_flume2d.yaml").string(),
                        "-o", (work / "fill").string(), "-t", "1"},
                       work);
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(work / "fill" / "wave_flume2d_fill.vtp"));
  EXPECT_TRUE(contains(r.out, "beach")) << r.out;
  // eagre_piston2d's paddle record is ../validation/eagre/..., beside cases/ in share/swell.
  const Result e =
      run({swell().string(), "fill", (data() / "cases" / "eagre_piston2d.yaml").string(), "-o",
           (work / "eagre").string(), "-t", "1"},
          work);
  EXPECT_EQ(e.rc, 0) << e.err;
  EXPECT_TRUE(fs::is_regular_file(work / "eagre" / "eagre_piston2d_fill.vtp"));
}

// ---------------------------------------------------------------------------------------------
// io/resources in this process (a test executable: no install prefix beside it).

struct EnvGuard {
  std::string name, old;
  bool had;
  EnvGuard(const char* n, const char* value) : name(n) {
    const char* o = std::getenv(n);
    had = o != nullptr;
    if (had) old = o;
    if (value)
      ::setenv(n, value, 1);
    else
      ::unsetenv(n);
  }
  ~EnvGuard() {
    if (had)
      ::setenv(name.c_str(), old.c_str(), 1);
    else
      ::unsetenv(name.c_str());
  }
};

TEST(Resources, LookupOrderAndSwellHomeAlone) {
  {
    const EnvGuard g("SWELL_HOME", nullptr);
    const auto roots = data_roots();
    ASSERT_EQ(roots.size(), 2u);
    EXPECT_EQ(roots[0].origin, "install prefix");
    EXPECT_EQ(roots[0].dir, installed_data_dir());
    EXPECT_EQ(roots[1].origin, "source tree");
    EXPECT_EQ(roots[1].dir, kSource);
    // From a test executable (build/tests/) the prefix guess holds nothing: the source tree.
    const auto f = find_data_file("validation/martin_moyce/validation.yaml");
    ASSERT_TRUE(f);
    EXPECT_EQ(*f, kSource / "validation" / "martin_moyce" / "validation.yaml");
  }
  {
    const EnvGuard g("SWELL_HOME", "");  // empty counts as unset
    EXPECT_EQ(data_roots().size(), 2u);
  }
  {
    const EnvGuard g("SWELL_HOME", "/nonexistent");
    ASSERT_EQ(data_roots().size(), 1u);
    std::vector<std::string> tried;
    EXPECT_FALSE(find_data_file("cases/dambreak2d.yaml", &tried));
    ASSERT_EQ(tried.size(), 1u);
    EXPECT_EQ(tried[0], "/nonexistent/cases/dambreak2d.yaml (SWELL_HOME)");
    try {
      require_data_file("cases/dambreak2d.yaml", "test");
      ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_TRUE(contains(e.what(),
                           "test: cases/dambreak2d.yaml not found (tried "
                           "/nonexistent/cases/dambreak2d.yaml (SWELL_HOME)); "
                           "SWELL_HOME is set"))
          << e.what();
    }
  }
}

TEST(Resources, PathWithin) {
  EXPECT_TRUE(path_within("/a/b/c.txt", "/a/b"));
  EXPECT_TRUE(path_within("/a/b/c.txt", "/a/b/"));
  EXPECT_TRUE(path_within("/a/b/x/../c", "/a/b"));
  EXPECT_FALSE(path_within("/a/bc/d", "/a/b"));
  EXPECT_FALSE(path_within("/a/b/../c", "/a/b"));
  EXPECT_FALSE(path_within("/a", "/a/b"));
  EXPECT_FALSE(path_within("/a/b", ""));
}

// `swell run` of the installed dam break with stdout redirected to a file, killed (SIGKILL)
// once its first checkpoint is on disk, i.e. after the header was printed: the header is in
// the redirected file (stdout is flushed at every line) and in OUTDIR/run.log.
TEST_F(Install, KilledRunKeepsItsHeaderInStdoutAndRunLog) {
  const fs::path work = root / "work" / "kill";
  fs::create_directories(work);
  const fs::path out = work / "run";
  test::ChildOptions o;
  o.cwd = work.string();
  o.unset = {"SWELL_HOME"};
  o.out = (work / "stdout.txt").string();
  o.err = (work / "stderr.txt").string();
  const pid_t pid =
      test::spawn({swell().string(), "run", (data() / "cases" / "dambreak2d.yaml").string(), "-o",
                   out.string(), "-t", "1"},
                  o);
  const auto t0 = std::chrono::steady_clock::now();
  while (!fs::exists(out / "checkpoint.h5") &&
         std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const bool started = fs::exists(out / "checkpoint.h5");
  ::kill(pid, SIGKILL);
  EXPECT_EQ(test::wait_exit(pid), -SIGKILL);
  ASSERT_TRUE(started) << read_text(work / "stderr.txt");
  const std::string stdout_text = read_text(work / "stdout.txt");
  const std::string log = read_text(out / "run.log");
  for (const std::string& part :
       {std::string("case dambreak2d (") + (data() / "cases" / "dambreak2d.yaml").string(),
        std::string("  body water (fluid): "), std::string("  total: ")}) {
    EXPECT_TRUE(contains(stdout_text, part)) << part << "\n--- stdout:\n" << stdout_text;
    EXPECT_TRUE(contains(log, part)) << part << "\n--- run.log:\n" << log;
  }
}

// ---------------------------------------------------------------------------------------------
// run.log of a complete run: header, progress lines (also with --quiet, which silences only
// the terminal's progress line) and the summary; a refused run writes none.

std::string tiny_case(double t_end) {
  std::ostringstream s;
  s << "name: tiny\ndim: 2\ndp: 0.004\ntime: {end: " << t_end << "}\nbodies:\n"
    << "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.2, 0.15]}}, "
       "layers: 3, open: [ymax]}\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.06, 0.08]}}}\n"
    << "output: {every: 0.01}\n";
  return s.str();
}

TEST(RunLog, CompleteRunLogsHeaderProgressAndSummary) {
  const fs::path work = fs::temp_directory_path() / "swell_test_runlog";
  fs::remove_all(work);
  fs::create_directories(work);
  std::ofstream(work / "tiny.yaml") << tiny_case(0.02);
  const fs::path swell = kBuild / "swell";
  const Result r = run({swell.string(), "run", (work / "tiny.yaml").string(), "-o",
                        (work / "out").string(), "-q", "-t", "1"},
                       work);
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string log = read_text(work / "out" / "run.log");
  EXPECT_TRUE(contains(log, "case tiny (")) << log;
  EXPECT_TRUE(contains(log, "/ 0.0200 s | step ")) << log;  // the last progress line
  EXPECT_TRUE(contains(log, "run summary: tiny")) << log;
  EXPECT_FALSE(contains(r.err, "| step ")) << "--quiet printed progress: " << r.err;
  EXPECT_TRUE(contains(r.out, "run summary: tiny"));
  // The log is one of the run's files: a new run refuses the folder, --overwrite replaces it.
  const Result again = run({swell.string(), "run", (work / "tiny.yaml").string(), "-o",
                            (work / "out").string(), "-q", "-t", "1"},
                           work);
  EXPECT_EQ(again.rc, 2) << again.err;
  // A restart appends to it (the time is raised, so the restart has steps to run).
  std::ofstream(work / "tiny.yaml") << tiny_case(0.03);
  const Result cont = run({swell.string(), "run", (work / "tiny.yaml").string(), "--restart",
                           (work / "out").string(), "-q", "-t", "1"},
                          work);
  ASSERT_EQ(cont.rc, 0) << cont.err;
  const std::string log2 = read_text(work / "out" / "run.log");
  EXPECT_EQ(log2.substr(0, log.size()), log);
  EXPECT_TRUE(contains(log2.substr(log.size()), "  restart from ")) << log2;
  EXPECT_TRUE(contains(log2.substr(log.size()), "/ 0.0300 s | step ")) << log2;
}

TEST(RunLog, ErrorThatEndsARunIsLoggedAndARefusedRunLeavesNoLog) {
  const fs::path work = fs::temp_directory_path() / "swell_test_runlog_err";
  fs::remove_all(work);
  fs::create_directories(work);
  const fs::path swell = kBuild / "swell";
  // Refused at set-up (exit 2): no folder, so no log.
  std::string bad = tiny_case(0.02);
  bad.replace(bad.find("dp: 0.004"), 9, "dp: 0.004\nphysics: {coefh: 9}");
  std::ofstream(work / "bad.yaml") << bad;
  const Result r1 = run(
      {swell.string(), "run", (work / "bad.yaml").string(), "-o", (work / "bad").string(), "-q"},
      work);
  EXPECT_EQ(r1.rc, 2) << r1.err;
  EXPECT_FALSE(fs::exists(work / "bad" / "run.log"));
  // Stopped by SIGTERM during the run: the stop and the restart command are in the log.
  std::ofstream(work / "long.yaml") << tiny_case(5.0);
  test::ChildOptions o;
  o.cwd = work.string();
  o.err = (work / "stderr.txt").string();
  const pid_t pid = test::spawn(
      {swell.string(), "run", (work / "long.yaml").string(), "-o", (work / "long").string(), "-q"},
      o);
  const auto t0 = std::chrono::steady_clock::now();
  while (!fs::exists(work / "long" / "checkpoint.h5") &&
         std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(pid, SIGTERM);
  EXPECT_EQ(test::wait_exit(pid), 143) << read_text(work / "stderr.txt");
  const std::string log = read_text(work / "long" / "run.log");
  EXPECT_TRUE(contains(log, "swell: stopped by SIGTERM at t = ")) << log;
  EXPECT_TRUE(contains(log, "continue with: swell run ")) << log;
}

// ---------------------------------------------------------------------------------------------
// scripts/setup with fake dpkg-query, apt-get and sudo first in PATH: a plan that removes a
// package stops it (exit 2, the package named, no real install); a plan that removes nothing
// installs with --no-remove.

struct FakeApt {
  fs::path dir, log;
  explicit FakeApt(const std::string& name, const std::string& installed,
                   const std::string& removed) {
    dir = fs::temp_directory_path() / ("swell_test_setup_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir / "bin");
    log = dir / "apt.log";
    auto script = [&](const std::string& file, const std::string& body) {
      const fs::path p = dir / "bin" / file;
      std::ofstream(p) << "#!/bin/sh\n" << body;
      fs::permissions(p, fs::perms::owner_all);
    };
    // Installed: every package in `installed`; others are missing.
    script("dpkg-query", "for p; do :; done\ncase \" " + installed +
                             " \" in *\" $p \"*) printf 'install ok installed';; *) exit 1;; "
                             "esac\n");
    std::string plan;
    for (std::istringstream in(removed); in;) {
      std::string p;
      if (in >> p) plan += "echo 'Remv " + p + " [1.0]'\n";
    }
    script("apt-get", "echo \"apt-get $*\" >> '" + log.string() +
                          "'\ncase \"$1\" in -s) echo 'Inst libvtk9-dev (9.1)'\n" + plan +
                          ";; esac\nexit 0\n");
    script("sudo", "\"$@\"\n");
  }
  Result run_setup() const {
    test::ChildOptions o;
    o.env = {"PATH=" + (dir / "bin").string() + ":/usr/bin:/bin"};
    o.out = (dir / "stdout.txt").string();
    o.err = (dir / "stderr.txt").string();
    const int rc = test::wait_exit(
        test::spawn({"/bin/bash", (kSource / "scripts" / "setup").string(), "--packages-only"}, o));
    return {rc, read_text(o.out), read_text(o.err)};
  }
};

// Everything scripts/setup needs except libvtk9-dev.
const std::string kAllButVtk =
    "build-essential cmake libeigen3-dev libcgal-dev libhdf5-dev libyaml-cpp-dev libgtest-dev "
    "libomp-dev libcli11-dev libssl-dev libopenmpi-dev python3-matplotlib python3-numpy "
    "python3-h5py";

TEST(Setup, StopsWhenTheInstallWouldRemoveParaViewsPython) {
  const FakeApt apt("paraview", kAllButVtk + " python3-paraview paraview", "python3-paraview");
  const Result r = apt.run_setup();
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "would REMOVE these installed packages")) << r.err;
  EXPECT_TRUE(contains(r.err, "python3-paraview")) << r.err;
  EXPECT_TRUE(contains(r.err, "ParaView's own binary release")) << r.err;
  const std::string calls = read_text(apt.log);
  EXPECT_TRUE(contains(calls, "apt-get -s install libvtk9-dev")) << calls;
  EXPECT_FALSE(contains(calls, "-y")) << calls;  // never a real install
}

TEST(Setup, StopsOnAnyRemovalAndInstallsWithNoRemoveOtherwise) {
  const FakeApt other("other", kAllButVtk, "libfoo1 libbar2");
  const Result r = other.run_setup();
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "libfoo1 libbar2")) << r.err;
  EXPECT_FALSE(contains(r.err, "python3-paraview")) << r.err;
  EXPECT_FALSE(contains(read_text(other.log), "-y"));

  const FakeApt clean("clean", kAllButVtk, "");
  const Result ok = clean.run_setup();
  EXPECT_EQ(ok.rc, 0) << ok.err;
  const std::string calls = read_text(clean.log);
  EXPECT_TRUE(contains(calls, "apt-get -s install libvtk9-dev")) << calls;
  EXPECT_TRUE(contains(calls, "apt-get install -y -qq --no-remove libvtk9-dev")) << calls;
}

}  // namespace
}  // namespace swell
