// End to end: the coarse damBreak-tutorial case (tests/data/foam_dambreak_small.yaml) run by
// interFoam through `swell foam` and by the SPH solver; both surge fronts must agree. Skipped,
// with a message, where OpenFOAM is not installed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "case/reader.hpp"
#include "foam/foam.hpp"
#include "run/run.hpp"

namespace fs = std::filesystem;
using namespace swell;

namespace {

struct Csv {
  std::string header;
  std::vector<double> t, v;  // first data column
};

Csv read_csv(const fs::path& p) {
  Csv c;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (c.header.empty()) {
      c.header = line;
      continue;
    }
    std::istringstream row(line);
    std::string a, b;
    std::getline(row, a, ',');
    std::getline(row, b, ',');
    if (b.empty()) continue;
    c.t.push_back(std::stod(a));
    c.v.push_back(std::stod(b));
  }
  return c;
}

double at(const Csv& c, double t) {
  for (std::size_t i = 1; i < c.t.size(); ++i)
    if (c.t[i] >= t) {
      const double f = (t - c.t[i - 1]) / (c.t[i] - c.t[i - 1]);
      return c.v[i - 1] + f * (c.v[i] - c.v[i - 1]);
    }
  return std::nan("");
}

}  // namespace

TEST(FoamEndToEnd, SphAndInterFoamAgreeOnTheFront) {
  std::string why;
  if (!openfoam_available(&why))
    GTEST_SKIP() << "OpenFOAM (interFoam) not installed: " << why
                 << " -- the SPH-vs-interFoam comparison did not run";
  const CaseSpec spec =
      load_case_file(std::string(SWELL_SOURCE_DIR) + "/tests/data/foam_dambreak_small.yaml");
  const fs::path root = fs::path(SWELL_BINARY_DIR) / "test_foam_e2e";
  fs::remove_all(root);

  FoamOptions fo;
  fo.out_dir = (root / "foam").string();
  fo.run = true;  // cell = dp = 8 mm
  std::ostringstream flog;
  FoamResult fr;
  try {
    fr = run_foam_case(spec, fo, flog);
  } catch (const FoamError& e) {
    FAIL() << e.what() << "\n" << flog.str();
  }
  EXPECT_TRUE(fr.ran);
  EXPECT_EQ(fr.cells, 73L * 73 - 12);  // the obstacle: 2 x 6 cells whose centre is inside
  EXPECT_GT(fr.steps, 50);

  RunOptions ro;
  ro.out_dir = (root / "sph").string();
  ro.threads = 2;
  ro.progress = false;
  std::ostringstream slog;
  ro.log = &slog;
  run_case(spec, ro);

  // Same files, same columns.
  for (const char* kind : {"front", "pressure", "height"}) {
    const fs::path a = fs::path(fr.gauge_dir) / (std::string("gauges_") + kind + ".csv");
    const fs::path b = fs::path(ro.out_dir) / (std::string("gauges_") + kind + ".csv");
    ASSERT_TRUE(fs::exists(a)) << a;
    EXPECT_EQ(read_csv(a).header, read_csv(b).header) << kind;
  }
  const Csv foam = read_csv(fs::path(fr.gauge_dir) / "gauges_front.csv");
  const Csv sph = read_csv(fs::path(ro.out_dir) / "gauges_front.csv");
  // While the surge runs towards the obstacle (it reaches it at ~0.13 s).
  for (double t : {0.05, 0.08, 0.10, 0.12}) {
    const double f = at(foam, t), s = at(sph, t);
    std::cout << "front at t = " << t << " s: SPH " << s << " m, interFoam " << f << " m ("
              << 100.0 * (f - s) / s << " %)\n";
    EXPECT_NEAR(f, s, 0.15 * s) << "t = " << t;
  }
  // The initial column holds (height gauge H1 in the column, t = 0.01 s, before it drops).
  const Csv hf = read_csv(fs::path(fr.gauge_dir) / "gauges_height.csv");
  EXPECT_NEAR(hf.v.front(), 0.292, 0.02);
  std::cout << "interFoam: " << fr.cells << " cells, " << fr.steps << " steps, " << fr.wall_seconds
            << " s\n";
}
