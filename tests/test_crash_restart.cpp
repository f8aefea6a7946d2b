// A run killed with SIGKILL at an arbitrary moment (possibly while writing a checkpoint or a
// snapshot) continues with `swell run --restart` and ends exactly where an uninterrupted run
// ends. Runs the real `swell` binary in a child process.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "io/hdf5_file.hpp"
#include "tests/child_process.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

const char* kCase =
    "name: crash_case\ndim: 2\ndp: 0.0028575\ntime: {end: 0.12}\n"
    "bodies:\n"
    "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.28575, 0.2286]}}, "
    "layers: 3, open: [ymax]}\n"
    "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.05715, 0.1143]}}}\n"
    "gauges:\n  - {name: front, kind: front}\n"
    "output: {every: 0.005, vtk: true, hdf5: true, checkpoint_every: 0.002, gauge_every: 0.001}\n";

using test::spawn;
using test::wait_exit;

TEST(CrashRestart, KilledRunContinuesToTheSameEnd) {
  const std::string swell = std::string(SWELL_BINARY_DIR) + "/swell";
  ASSERT_TRUE(fs::exists(swell)) << swell;
  const fs::path root = fs::temp_directory_path() / "swell_test_crash";
  fs::remove_all(root);
  fs::create_directories(root);
  const std::string case_path = (root / "crash_case.yaml").string();
  std::ofstream(case_path) << kCase;
  const fs::path full = root / "full", killed = root / "killed";

  ASSERT_EQ(wait_exit(spawn({swell, "run", case_path, "-o", full.string(), "-q", "-t", "1"})), 0);

  // Several kills at pseudo-random moments after the first checkpoints exist; each time the
  // run is resumed from whatever the kill left behind.
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> delay_ms(0, 400);
  pid_t pid = spawn({swell, "run", case_path, "-o", killed.string(), "-q", "-t", "1"});
  for (int kill_round = 0; kill_round < 3; ++kill_round) {
    const auto t0 = std::chrono::steady_clock::now();
    while (!fs::exists(killed / "checkpoint.h5.prev") &&
           std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    kill(pid, SIGKILL);
    const int rc = wait_exit(pid);
    std::cout << "  kill round " << kill_round << ": exit " << rc << "\n";
    if (rc == 0) break;  // finished before the kill landed: nothing left to resume
    EXPECT_EQ(rc, -SIGKILL);
    pid = spawn({swell, "run", case_path, "--restart", killed.string(), "-q", "-t", "2"});
  }
  ASSERT_EQ(wait_exit(pid), 0) << "the resumed run failed";

  const auto a = read_checkpoint<2>((full / "checkpoint.h5").string());
  const auto b = read_checkpoint<2>((killed / "checkpoint.h5").string());
  EXPECT_EQ(a.clock.steps, b.clock.steps);
  EXPECT_EQ(a.clock.time, b.clock.time);
  ASSERT_EQ(a.particles.total(), b.particles.total());
  EXPECT_EQ(a.particles.id, b.particles.id);
  EXPECT_EQ(a.particles.rho, b.particles.rho);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.particles.total(); ++i)
    differing +=
        a.particles.pos[i] != b.particles.pos[i] || a.particles.vel[i] != b.particles.vel[i];
  EXPECT_EQ(differing, 0u);
  // The snapshot series has the same times, without duplicates.
  const auto sa = list_snapshots((full / "crash_case.h5").string());
  const auto sb = list_snapshots((killed / "crash_case.h5").string());
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t i = 0; i < sa.size(); ++i) EXPECT_EQ(sa[i].time, sb[i].time);
}

}  // namespace
}  // namespace swell
