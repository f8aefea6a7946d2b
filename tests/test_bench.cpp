// The benchmark driver works end to end (never timed here: bench/ measures speed, tests only
// check that the measurement runs and reports what it says). A coarse B2D and a two-point
// B3D sweep of a few steps each.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

std::string run(const std::string& cmd, int* status) {
  std::string out;
  std::FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  char buf[4096];
  while (p && std::fgets(buf, sizeof buf, p)) out += buf;
  *status = p ? ::pclose(p) : -1;
  return out;
}

std::map<std::string, double> parse_result(const std::string& out) {
  std::map<std::string, double> v;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("bench-result", 0) != 0) continue;
    std::istringstream kv(line.substr(12));
    for (std::string f; kv >> f;) {
      const auto eq = f.find('=');
      v[f.substr(0, eq)] = std::stod(f.substr(eq + 1));
    }
  }
  return v;
}

TEST(Bench, SingleRunReportsCountsStepsAndMemory) {
  const std::string exe = std::string(SWELL_BINARY_DIR) + "/swell_bench_run";
  ASSERT_TRUE(fs::exists(exe)) << exe;
  int status = 0;
  const std::string out = run(
      exe + " " + SWELL_SOURCE_DIR "/bench/cases/b2d.yaml --dp 0.04 " + "--steps 5 --warmup 2 -t 1",
      &status);
  ASSERT_EQ(status, 0) << out;
  const auto v = parse_result(out);
  ASSERT_FALSE(v.empty()) << out;
  // dp 0.04: the 1 m x 2 m column holds 25 x 50 fluid particles.
  EXPECT_EQ(v.at("fluid"), 1250.0);
  EXPECT_GT(v.at("particles"), v.at("fluid"));
  EXPECT_EQ(v.at("steps"), 5.0);
  EXPECT_GT(v.at("pss"), 0.0);
  EXPECT_NEAR(v.at("pss"), v.at("particles") * v.at("steps") / v.at("wall"), 1e-6 * v.at("pss"));
  EXPECT_GT(v.at("rss_peak_kb"), 0.0);
  EXPECT_GE(v.at("rss_peak_kb"), v.at("rss_base_kb"));
  // The phases never add up to more than the loop.
  EXPECT_LE(v.at("neighbour") + v.at("interaction") + v.at("integration"), v.at("wall") * 1.0001);
}

TEST(Bench, SingleRunToAnEndTimeAndBadInput) {
  const std::string exe = std::string(SWELL_BINARY_DIR) + "/swell_bench_run";
  int status = 0;
  std::string out =
      run(exe + " " + SWELL_SOURCE_DIR "/bench/cases/b3d.yaml --dp 0.06 --end 0.002", &status);
  ASSERT_EQ(status, 0) << out;
  const auto v = parse_result(out);
  EXPECT_GE(v.at("sim_time"), 0.002);
  EXPECT_GT(v.at("steps"), 1.0);
  out = run(exe + " /nonexistent/case.yaml", &status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("/nonexistent/case.yaml"), std::string::npos) << out;
}

TEST(Bench, SweepWritesCsvWithOneRowPerDp) {
  const fs::path out_dir = fs::temp_directory_path() / "swell_test_bench_sweep";
  fs::remove_all(out_dir);
  int status = 0;
  const std::string out =
      run(std::string(SWELL_BINARY_DIR) + "/swell bench --sweep --sweep-dp 0.06,0.05 " +
              "--sweep-steps 3 --repeats 1 --threads 1 -o " + out_dir.string(),
          &status);
  ASSERT_EQ(status, 0) << out;
  std::ifstream in(out_dir / "scaling.csv");
  ASSERT_TRUE(in) << out;
  int rows = 0;
  double n_prev = 0.0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line.rfind("dp,", 0) == 0) continue;
    ++rows;
    std::istringstream f(line);
    std::string dp, n;
    std::getline(f, dp, ',');
    std::getline(f, n, ',');
    EXPECT_GT(std::stod(n), n_prev);  // finer dp, more particles
    n_prev = std::stod(n);
  }
  EXPECT_EQ(rows, 2);
}

TEST(Bench, UnknownCaseIsAnInputError) {
  int status = 0;
  const std::string out = run(std::string(SWELL_BINARY_DIR) + "/swell bench nosuchcase", &status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("nosuchcase"), std::string::npos) << out;
}

}  // namespace
