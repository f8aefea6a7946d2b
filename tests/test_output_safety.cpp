// A run never loses or corrupts a user's work (issue #15, part A), tested on the real `swell`
// binary in child processes: kills aimed at snapshot writes, folders that already hold a run,
// checkpoints of another case, unsafe case names, a file size limit, SIGINT/SIGTERM, option
// errors and two runs on one folder. Each error path asserts its exit code and message.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "case/identity.hpp"
#include "case/reader.hpp"
#include "io/hdf5_file.hpp"
#include "io/run_folder.hpp"
#include "tests/child_process.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

const std::string kSwell = std::string(SWELL_BINARY_DIR) + "/swell";

// ~700 particles: a run to 0.03 s takes well under a second.
std::string small_case(double t_end, const std::string& extra = "",
                       const std::string& output = "every: 0.005, checkpoint_every: 0.0025") {
  std::ostringstream s;
  s << "name: small\ndim: 2\ndp: 0.004\ntime: {end: " << t_end << "}\n"
    << extra << "bodies:\n"
    << "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.2, 0.15]}}, "
       "layers: 3, open: [ymax]}\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.06, 0.08]}}}\n"
    << "gauges:\n  - {name: front, kind: front}\n"
    << "output: {vtk: true, hdf5: true, " << output << "}\n";
  return s.str();
}

fs::path fresh_root(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("swell_test_safety_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string write_case(const fs::path& dir, const std::string& file, const std::string& text) {
  const std::string path = (dir / file).string();
  std::ofstream(path) << text;
  return path;
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

using test::ChildOptions;
using test::wait_exit;

// Starts `swell args...` with stdout discarded and stderr into `err`.
pid_t spawn(const std::vector<std::string>& args, const fs::path& err, ChildOptions o = {}) {
  std::vector<std::string> all = {kSwell};
  all.insert(all.end(), args.begin(), args.end());
  o.err = err.string();
  return test::spawn(all, o);
}

// The largest file below `dir` whose name does not start with `skip`.
std::uintmax_t largest_file(const fs::path& dir, const std::string& skip) {
  std::uintmax_t largest = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && !e.path().filename().string().starts_with(skip))
      largest = std::max(largest, e.file_size());
  return largest;
}

struct Result {
  int rc;
  std::string err;
};

Result run_swell(const std::vector<std::string>& args, const fs::path& root,
                 const ChildOptions& o = {}) {
  const fs::path err = root / "stderr.txt";
  const int rc = wait_exit(spawn(args, err, o));
  return {rc, read_text(err)};
}

void wait_for(const fs::path& p) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!fs::exists(p) && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_TRUE(fs::exists(p)) << p;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The final states of two runs are bitwise equal.
void expect_same_end(const fs::path& a, const fs::path& b) {
  const auto ca = read_checkpoint<2>((a / "checkpoint.h5").string());
  const auto cb = read_checkpoint<2>((b / "checkpoint.h5").string());
  EXPECT_EQ(ca.clock.steps, cb.clock.steps);
  EXPECT_EQ(ca.clock.time, cb.clock.time);
  EXPECT_EQ(ca.particles.id, cb.particles.id);
  EXPECT_EQ(ca.particles.pos, cb.particles.pos);
  EXPECT_EQ(ca.particles.vel, cb.particles.vel);
  EXPECT_EQ(ca.particles.rho, cb.particles.rho);
}

// Every snapshot of run `a` is in run `b`'s run file with the same step, time and positions.
void expect_same_snapshots(const fs::path& a, const fs::path& b) {
  const std::string fa = (a / "small.h5").string(), fb = (b / "small.h5").string();
  const auto sa = list_snapshots(fa), sb = list_snapshots(fb);
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t i = 0; i < sa.size(); ++i) {
    EXPECT_EQ(sa[i].step, sb[i].step);
    EXPECT_EQ(sa[i].time, sb[i].time);
    EXPECT_EQ(read_snapshot<2>(fa, sa[i]).pos, read_snapshot<2>(fb, sb[i]).pos) << i;
  }
}

// The VTK files in OUT/vtk and the files the .pvd lists are the same set.
void expect_pvd_lists_every_vtk_file(const fs::path& out) {
  std::set<std::string> listed, present;
  const std::string pvd = read_text(out / "small.pvd");
  const std::regex file_attr("file=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), file_attr);
       it != std::sregex_iterator(); ++it)
    listed.insert((*it)[1]);
  for (const auto& e : fs::directory_iterator(out / "vtk"))
    present.insert("vtk/" + e.path().filename().string());
  EXPECT_EQ(listed, present);
}

// SWELL_TEST_KILL_AT makes the writer SIGKILL itself inside the N-th snapshot write: once
// with the snapshot's file complete but not yet renamed, once with the snapshot in place but
// the run file's new index not yet renamed. After --restart no snapshot is missing: the run
// file lists exactly the snapshots of an uninterrupted run, with the same data.
TEST(OutputSafety, KillInsideSnapshotWriteLosesNoEarlierSnapshot) {
  const fs::path root = fresh_root("kill_snapshot");
  const std::string c = write_case(root, "small.yaml", small_case(0.04));
  const fs::path full = root / "full";
  ASSERT_EQ(run_swell({"run", c, "-o", full.string(), "-q", "-t", "1"}, root).rc, 0);
  const std::size_t n_full = list_snapshots((full / "small.h5").string()).size();
  ASSERT_EQ(n_full, 9u);  // t = 0, 0.005, ..., 0.04
  // `swell probe` reads the run file: the same rows from the killed and continued run.
  auto probe = [&](const fs::path& out) {
    const fs::path csv = root / "probe.csv";
    fs::remove(csv);
    EXPECT_EQ(run_swell({"probe", out.string(), "--at", "0.02,0.01", "-o", csv.string()}, root).rc,
              0);
    // Without the comment lines (the folder's name, the provenance of the probe command).
    std::istringstream in(read_text(csv));
    std::string rows;
    for (std::string line; std::getline(in, line);)
      if (!line.starts_with("#")) rows += line + "\n";
    return rows;
  };
  const std::string probe_full = probe(full);
  ASSERT_EQ(std::count(probe_full.begin(), probe_full.end(), '\n'), 9 + 1);  // + the header
  // -o into a folder that does not exist: exit 2 naming it, before reading the run; nothing made.
  {
    const fs::path missing = root / "no_such_folder";
    const auto r = run_swell(
        {"probe", full.string(), "--at", "0.02,0.01", "-o", (missing / "p.csv").string()}, root);
    EXPECT_EQ(r.rc, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "no_such_folder")) << r.err;
    EXPECT_FALSE(fs::exists(missing));
  }

  for (const std::string point : {"snapshot-data", "snapshot-index"}) {
    for (const int n : {3, 6}) {  // the first checkpoint comes with snapshot 2
      SCOPED_TRACE(point + ":" + std::to_string(n));
      const fs::path out = root / (point + std::to_string(n));
      ChildOptions o;
      o.env = {"SWELL_TEST_KILL_AT=" + point + ":" + std::to_string(n)};
      EXPECT_EQ(run_swell({"run", c, "-o", out.string(), "-q", "-t", "1"}, root, o).rc, -SIGKILL);
      // The run file, as the kill left it, reads and lists the snapshots before the n-th.
      EXPECT_EQ(list_snapshots((out / "small.h5").string()).size(), std::size_t(n - 1));
      const Result r = run_swell({"run", c, "--restart", out.string(), "-q", "-t", "1"}, root);
      ASSERT_EQ(r.rc, 0) << r.err;
      expect_same_snapshots(full, out);
      expect_same_end(full, out);
      expect_pvd_lists_every_vtk_file(out);
      EXPECT_EQ(probe(out), probe_full);
    }
  }
}

TEST(OutputSafety, NewRunRefusesAFolderHoldingARunUnlessOverwrite) {
  const fs::path root = fresh_root("overwrite");
  const std::string a = write_case(root, "a.yaml", small_case(0.03));
  const fs::path out = root / "out";
  ASSERT_EQ(run_swell({"run", a, "-o", out.string(), "-q", "-t", "1"}, root).rc, 0);
  const std::string ck = read_text(out / "checkpoint.h5");

  // Another case (fewer, sparser snapshots) into the same folder: refused, nothing touched.
  const std::string b = write_case(root, "b.yaml", small_case(0.02, "", "every: 0.01"));
  const Result r = run_swell({"run", b, "-o", out.string(), "-q", "-t", "1"}, root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(contains(r.err, "output folder " + out.string() + " already holds a run")) << r.err;
  EXPECT_TRUE(contains(r.err, "--overwrite")) << r.err;
  EXPECT_EQ(read_text(out / "checkpoint.h5"), ck);
  EXPECT_EQ(list_snapshots((out / "small.h5").string()).size(), 7u);

  // With --overwrite: the earlier run's files are gone, no stale snapshot is left.
  std::ofstream(out / "notes.txt") << "a user's file";
  ASSERT_EQ(run_swell({"run", b, "-o", out.string(), "-q", "-t", "1", "--overwrite"}, root).rc, 0);
  EXPECT_EQ(list_snapshots((out / "small.h5").string()).size(), 3u);  // 0, 0.01, 0.02
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(out / "snapshots")) ++files;
  EXPECT_EQ(files, 3u);
  expect_pvd_lists_every_vtk_file(out);
  EXPECT_EQ(read_text(out / "notes.txt"), "a user's file");
}

TEST(OutputSafety, RestartRefusesACheckpointOfAnotherCase) {
  const fs::path root = fresh_root("other_case");
  const std::string a = write_case(root, "a.yaml", small_case(0.02));
  const fs::path out = root / "out";
  ASSERT_EQ(run_swell({"run", a, "-o", out.string(), "-q", "-t", "1"}, root).rc, 0);
  // Same particle count, other physics: the particle count alone would not tell.
  const std::string b = write_case(root, "b.yaml", small_case(0.04, "physics: {coefsound: 15}\n"));
  const Result r = run_swell({"run", b, "--restart", out.string(), "-q", "-t", "1"}, root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(contains(r.err, "checkpoint.h5 was written by case 'small' (" + a + "), and " + b +
                                  " differs from it"))
      << r.err;
  // Raising time.end is what a restart is for: accepted.
  const std::string longer = write_case(root, "a2.yaml", small_case(0.03));
  EXPECT_EQ(run_swell({"run", longer, "--restart", out.string(), "-q", "-t", "1"}, root).rc, 0);
}

TEST(OutputSafety, CaseIdentityCoversTheCaseAndItsInputFiles) {
  const fs::path root = fresh_root("identity");
  std::ofstream(root / "paddle.csv") << "t,x\n0,0\n1,0.1\n";
  auto spec_of = [&](const std::string& text) {
    CaseSpec s;
    s.name = "c";
    s.dim = 2;
    s.file = (root / "c.yaml").string();
    s.text = text;
    return s;
  };
  const std::string base = "dim: 2\ntime: {end: 1}\nmotion: {type: file, file: paddle.csv}\n";
  const std::string id = case_identity(spec_of(base));
  EXPECT_EQ(id.size(), 64u);
  EXPECT_EQ(case_identity(spec_of("# a comment\ndim: 2\ntime: {end: 5}\nmotion: {type: file, "
                                  "file: paddle.csv}\n")),
            id);
  EXPECT_NE(case_identity(spec_of("dim: 2\ntime: {end: 1, cfl: 0.1}\nmotion: {type: file, file: "
                                  "paddle.csv}\n")),
            id);
  std::ofstream(root / "paddle.csv") << "t,x\n0,0\n1,0.2\n";  // same case text, other file bytes
  EXPECT_NE(case_identity(spec_of(base)), id);
}

TEST(OutputSafety, CaseNamesAreRestrictedToASafeSet) {
  for (const std::string& name : std::vector<std::string>{
           "../other/base", "/tmp/abs", "\"a\\0b\"", ".hidden", "a b", std::string(101, 'x')}) {
    SCOPED_TRACE(name);
    try {
      parse_case_text("name: " + name + "\n" + small_case(0.01).substr(12), "case.yaml");
      FAIL() << "accepted";
    } catch (const CaseError& e) {
      EXPECT_TRUE(contains(e.what(),
                           "case.yaml:1: name: expected 1 to 100 characters from A-Z "
                           "a-z 0-9 . _ -, not starting with '.'"))
          << e.what();
      // The NUL is shown, not the end of the message.
      if (name == "\"a\\0b\"") EXPECT_TRUE(contains(e.what(), "'a\\x00b'")) << e.what();
    }
  }
  EXPECT_EQ(parse_case_text(small_case(0.01), "x.yaml").name, "small");
  // Without `name`, the file's name made safe.
  EXPECT_EQ(parse_case_text(small_case(0.01).substr(12), "dir/my case (v2).yaml").name,
            "my_case__v2_");

  // The command refuses with exit 2 and writes nothing.
  const fs::path root = fresh_root("names");
  const std::string c =
      write_case(root, "bad.yaml", "name: ../escaped\n" + small_case(0.01).substr(12));
  const Result r = run_swell({"run", c, "-o", (root / "out").string(), "-q"}, root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(contains(r.err, c + ":1: name: expected")) << r.err;
  EXPECT_FALSE(fs::exists(root / "out"));
  EXPECT_FALSE(fs::exists(root / "escaped.h5"));
}

// A file size limit (ulimit -f): the write that passes it fails with EFBIG instead of a
// SIGXFSZ kill; the run exits 1 naming the file, and the checkpoint before it loads and
// continues to the same end as an uninterrupted run.
TEST(OutputSafety, FileSizeLimitExitsOneAndKeepsTheCheckpoint) {
  const fs::path root = fresh_root("fsize");
  // Many velocity gauges sampled often: the gauge CSV outgrows every other file.
  std::string gauges = "gauges:\n";
  for (int k = 0; k < 12; ++k)
    gauges += "  - {name: V" + std::to_string(k) + ", kind: velocity, at: [0.0" +
              std::to_string(1 + k % 5) + ", 0.02]}\n";
  std::string text =
      small_case(0.06, "", "every: 0.01, checkpoint_every: 0.005, gauge_every: 5e-5");
  const std::string front = "gauges:\n  - {name: front, kind: front}\n";
  text.replace(text.find(front), front.size(), gauges);
  const std::string c = write_case(root, "small.yaml", text);
  const fs::path full = root / "full", limited = root / "limited";
  ASSERT_EQ(run_swell({"run", c, "-o", full.string(), "-q", "-t", "1"}, root).rc, 0);
  const std::uintmax_t largest_other = largest_file(full, "gauges_velocity.csv");
  const rlim_t limit = largest_other * 3 / 2;
  ASSERT_GT(fs::file_size(full / "gauges_velocity.csv"), 2 * limit);

  ChildOptions o;
  o.file_size = limit;
  const Result r = run_swell({"run", c, "-o", limited.string(), "-q", "-t", "1"}, root, o);
  EXPECT_EQ(r.rc, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "error: cannot write gauge file " +
                                  (limited / "gauges_velocity.csv").string() + ": File too large"))
      << r.err;
  const auto ck = read_checkpoint<2>(latest_valid_checkpoint((limited / "checkpoint.h5").string()));
  EXPECT_GT(ck.clock.time, 0.0);
  EXPECT_LT(ck.clock.time, 0.06);
  EXPECT_FALSE(fs::exists(limited / "checkpoint.h5.tmp"));
  const Result again = run_swell({"run", c, "--restart", limited.string(), "-q", "-t", "1"}, root);
  ASSERT_EQ(again.rc, 0) << again.err;
  expect_same_end(full, limited);
  EXPECT_EQ(read_text(full / "gauges_velocity.csv"), read_text(limited / "gauges_velocity.csv"));
}

// A file size limit met by an HDF5 write (the checkpoint, the largest file): exit 1 with
// HDF5's reason, not a crash in HDF5's exit handler; no temporary file left, the snapshots
// already written read back.
TEST(OutputSafety, FailedHdf5WriteExitsOneCleanly) {
  const fs::path root = fresh_root("fsize_hdf5");
  const std::string c = write_case(root, "small.yaml", small_case(0.02));
  const fs::path full = root / "full", limited = root / "limited";
  ASSERT_EQ(run_swell({"run", c, "-o", full.string(), "-q", "-t", "1"}, root).rc, 0);
  const std::uintmax_t largest_other = largest_file(full, "checkpoint");
  const std::uintmax_t checkpoint = fs::file_size(full / "checkpoint.h5");
  ASSERT_LT(largest_other, checkpoint);
  ChildOptions o;
  o.file_size = (largest_other + checkpoint) / 2;
  const Result r = run_swell({"run", c, "-o", limited.string(), "-q", "-t", "1"}, root, o);
  EXPECT_EQ(r.rc, 1) << r.err;
  EXPECT_TRUE(
      contains(r.err, "error: HDF5 file '" + (limited / "checkpoint.h5.tmp").string() + "': "))
      << r.err;
  EXPECT_TRUE(contains(r.err, "file write failed: File too large)")) << r.err;
  for (const auto& e : fs::recursive_directory_iterator(limited))
    EXPECT_FALSE(e.path().string().ends_with(".tmp")) << e.path();
  const auto snaps = list_snapshots((limited / "small.h5").string());
  ASSERT_FALSE(snaps.empty());
  for (const auto& s : snaps) EXPECT_NO_THROW(read_snapshot<2>((limited / "small.h5").string(), s));
}

// SIGINT (exit 130) and SIGTERM (exit 143) stop the run between two steps with a checkpoint
// and the command that continues it; continued, the run ends as if never stopped.
TEST(OutputSafety, SignalsWriteACheckpointAndTheRestartCommand) {
  const fs::path root = fresh_root("signals");
  const std::string c = write_case(root, "small.yaml", small_case(0.12));
  const fs::path full = root / "full", stopped = root / "stopped";
  ASSERT_EQ(run_swell({"run", c, "-o", full.string(), "-q", "-t", "1"}, root).rc, 0);

  std::vector<std::string> args = {"run", c, "-o", stopped.string(), "-q", "-t", "1"};
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(sig);
    fs::remove(stopped / "checkpoint.h5.prev");
    const fs::path err = root / "stderr.txt";
    const pid_t pid = spawn(args, err);
    wait_for(stopped / "checkpoint.h5.prev");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    kill(pid, sig);
    const int rc = wait_exit(pid);
    const std::string text = read_text(err);
    ASSERT_EQ(rc, 128 + sig) << text;
    EXPECT_TRUE(contains(text, std::string("swell: stopped by ") +
                                   (sig == SIGINT ? "SIGINT" : "SIGTERM") + " at t = "))
        << text;
    EXPECT_TRUE(contains(text, "continue with: swell run " + c + " --restart " + stopped.string()))
        << text;
    const auto ck = read_checkpoint<2>((stopped / "checkpoint.h5").string());
    EXPECT_LT(ck.clock.time, 0.12);
    args = {"run", c, "--restart", stopped.string(), "-q", "-t", "1"};
  }
  const Result r = run_swell(args, root);
  ASSERT_EQ(r.rc, 0) << r.err;
  expect_same_end(full, stopped);
  expect_same_snapshots(full, stopped);
  EXPECT_EQ(read_text(full / "gauges_front.csv"), read_text(stopped / "gauges_front.csv"));
}

// A second signal ends the run at once. Both are made pending while the child is stopped, so
// the second arrives before the first one's checkpoint is written (SIGINT and SIGTERM: two
// signals of one kind would merge into one).
TEST(OutputSafety, SecondSignalExitsAtOnce) {
  const fs::path root = fresh_root("second_signal");
  const std::string c = write_case(root, "small.yaml", small_case(0.5));
  const fs::path out = root / "out", err = root / "stderr.txt";
  const pid_t pid = spawn({"run", c, "-o", out.string(), "-q", "-t", "1"}, err);
  wait_for(out / "checkpoint.h5.prev");
  kill(pid, SIGSTOP);
  kill(pid, SIGINT);
  kill(pid, SIGTERM);
  kill(pid, SIGCONT);
  const int rc = wait_exit(pid);  // the code of whichever signal came second
  EXPECT_TRUE(rc == 128 + SIGTERM || rc == 128 + SIGINT) << rc;
  const std::string text = read_text(err);
  EXPECT_TRUE(contains(text, "swell: second signal: stopping now, without a new checkpoint"))
      << text;
  EXPECT_FALSE(contains(text, "continue with")) << text;
  EXPECT_NO_THROW(read_checkpoint<2>(latest_valid_checkpoint((out / "checkpoint.h5").string())));
}

TEST(OutputSafety, SecondRunOnABusyFolderIsRefused) {
  const fs::path root = fresh_root("busy");
  const std::string c = write_case(root, "small.yaml", small_case(0.5));
  const fs::path out = root / "out";
  const pid_t pid = spawn({"run", c, "-o", out.string(), "-q", "-t", "1"}, root / "first.txt");
  wait_for(out / "checkpoint.h5");
  for (const auto& args : {std::vector<std::string>{"run", c, "-o", out.string(), "--overwrite"},
                           std::vector<std::string>{"run", c, "--restart", out.string()}}) {
    const Result r = run_swell(args, root);
    EXPECT_EQ(r.rc, 2);
    EXPECT_TRUE(contains(r.err, "error: output folder " + out.string() +
                                    " is in use by another swell run (pid " + std::to_string(pid) +
                                    ", lock "))
        << r.err;
  }
  kill(pid, SIGKILL);
  EXPECT_EQ(wait_exit(pid), -SIGKILL);
  EXPECT_FALSE(list_snapshots((out / "small.h5").string()).empty());
  // The lock went with the process.
  EXPECT_NO_THROW(OutputLock lock(out.string()));
}

TEST(OutputSafety, OptionErrorsExitTwoWithAUsefulMessage) {
  const fs::path root = fresh_root("options");
  const std::string c = write_case(root, "small.yaml", small_case(0.01));
  Result r = run_swell({}, root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(contains(r.err, "error: a command is required")) << r.err;
  EXPECT_TRUE(contains(r.err, "Subcommands:") && contains(r.err, "probe")) << r.err;
  r = run_swell({"frobnicate"}, root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(contains(r.err, "error: unknown command 'frobnicate'")) << r.err;
  EXPECT_TRUE(contains(r.err, "Subcommands:")) << r.err;
  r = run_swell({"run", c, "--threads", "0"}, root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(contains(r.err, "--threads: expected a whole number >= 1, got '0'")) << r.err;
  EXPECT_LT(r.err.size(), 120u) << r.err;
  r = run_swell({"run", c, "--bogus"}, root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(contains(r.err, "--bogus")) << r.err;
  r = run_swell({"run", c, "--overwrite", "--restart", (root / "x").string()}, root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(contains(r.err, "--restart excludes --overwrite")) << r.err;
  r = run_swell({"probe", (root / "x").string(), "--at", "0,0", "--offset", "-1", "--kind", "mass"},
                root);
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(run_swell({"--version"}, root).rc, 0);
}

}  // namespace
}  // namespace swell
