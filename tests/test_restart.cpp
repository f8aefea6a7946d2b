// Restart is tested by construction: a run stopped half-way and continued from its checkpoint
// ends with the same particles, bit for bit, as a run that never stopped (the pair loop is a
// gather with a fixed order per particle and the only reductions are maxima, so results do
// not even depend on the thread count). Also: `swell probe` on saved snapshots reproduces the
// in-run gauge, and the HDF5 run file holds the documented layout.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/probe_command.hpp"
#include "case/reader.hpp"
#include "io/hdf5_file.hpp"
#include "run/run.hpp"
#include "solver/gauges.hpp"
#include "solver/physics/kernels.hpp"
#include "tests/case_run.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

// A coarse Martin & Moyce column (a/dp = 20) with one gauge of each kind.
std::string case_text(double t_end, int threads_note = 0) {
  std::ostringstream s;
  s << "name: restart_case\ndim: 2\ndp: 0.0028575\n"
    << "time: {end: " << t_end << "}\n"
    << "bodies:\n"
    << "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.28575, 0.2286]}}, "
       "layers: 3, open: [ymax]}\n"
    << "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.05715, 0.1143]}}}\n"
    << "gauges:\n"
    << "  - {name: P0, kind: pressure, at: [0.0, 0.01], normal: [1, 0]}\n"
    << "  - {name: H0, kind: height, at: [0.03, 0.0]}\n"
    << "  - {name: V0, kind: velocity, at: [0.05, 0.01]}\n"
    << "  - {name: Ftank, kind: force, body: tank}\n"
    << "  - {name: front, kind: front}\n"
    << "output: {every: 0.01, vtk: false, hdf5: true, gauge_every: 0.01}\n";
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("swell_test_" + name);
  fs::remove_all(d);
  return d;
}

RunSummary run(const std::string& text, const fs::path& dir, bool restart, int threads) {
  return test::run_case_text(text, "restart_case.yaml", dir, restart, threads);
}

using test::read_text;

TEST(Restart, ContinuedRunMatchesUninterruptedRunBitwise) {
  const fs::path a = fresh_dir("full"), b = fresh_dir("split");
  run(case_text(0.06), a, false, 2);
  run(case_text(0.03), b, false, 1);  // stops half-way ...
  run(case_text(0.06), b, true, 2);   // ... and continues, with another thread count

  const auto ca = read_checkpoint<2>((a / "checkpoint.h5").string());
  const auto cb = read_checkpoint<2>((b / "checkpoint.h5").string());
  EXPECT_EQ(ca.clock.steps, cb.clock.steps);
  EXPECT_EQ(ca.clock.time, cb.clock.time);
  EXPECT_EQ(ca.clock.dt, cb.clock.dt);
  ASSERT_EQ(ca.particles.total(), cb.particles.total());
  ASSERT_EQ(ca.particles.size(), cb.particles.size());
  EXPECT_EQ(ca.particles.id, cb.particles.id);
  EXPECT_EQ(ca.particles.rho, cb.particles.rho);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < ca.particles.total(); ++i)
    differing +=
        ca.particles.pos[i] != cb.particles.pos[i] || ca.particles.vel[i] != cb.particles.vel[i];
  EXPECT_EQ(differing, 0u) << "positions/velocities differ after restart";
  // The particles did move (the comparison is not between two initial states).
  EXPECT_GT(ca.clock.steps, 100);

  // Gauge and diagnostics series read as if the run never stopped.
  for (const char* f : {"gauges_pressure.csv", "gauges_height.csv", "gauges_velocity.csv",
                        "gauges_force.csv", "gauges_front.csv", "diagnostics.csv"})
    EXPECT_EQ(read_text(a / f), read_text(b / f)) << f;
  EXPECT_EQ(list_snapshots((a / "restart_case.h5").string()).size(),
            list_snapshots((b / "restart_case.h5").string()).size());
}

TEST(Restart, MissingCheckpointIsAClearError) {
  const fs::path d = fresh_dir("nockpt");
  try {
    run(case_text(0.01), d, true, 1);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no checkpoint"), std::string::npos) << e.what();
  }
}

// `every: step` writes a gauge's raw series, a row after every step; a sensor face's interval
// means (the same face with an `every`) are the dt-weighted means of that series over their
// intervals; a restart neither repeats nor drops a row.
TEST(SensorFace, EveryStepWritesTheRawSeriesTheIntervalMeansAverage) {
  std::string text = case_text(0.03);
  const std::string faces =
      "  - {name: S_raw, kind: pressure, at: [0.0, 0.01], normal: [1, 0], size: 0.01, every: "
      "step}\n"
      "  - {name: S, kind: pressure, at: [0.0, 0.01], normal: [1, 0], size: 0.01}\n";
  text.insert(text.find("output:"), faces);
  std::string half = text;
  half.replace(half.find("end: 0.03"), 9, "end: 0.015");
  const fs::path a = fresh_dir("every_step"), b = fresh_dir("every_step_split");
  const RunSummary sum = run(text, a, false, 2);
  run(half, b, false, 1);
  run(text, b, true, 2);
  // Rows of gauges_pressure.csv: time, then the columns P0, S_raw, S (empty where not due).
  const auto rows = [](const std::string& csv) {
    std::vector<std::vector<std::string>> r;
    std::istringstream in(csv);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || line[0] == 't') continue;
      std::vector<std::string> cells;
      std::string cell;
      std::istringstream ls(line);
      while (std::getline(ls, cell, ',')) cells.push_back(cell);
      while (cells.size() < 4) cells.emplace_back();
      r.push_back(cells);
    }
    return r;
  };
  const auto ra = rows(read_text(a / "gauges_pressure.csv"));
  EXPECT_EQ(ra, rows(read_text(b / "gauges_pressure.csv")));  // the restart: the same rows
  std::vector<double> t, raw;
  int means = 0;
  double acc = 0.0, acc_t = 0.0, t_prev = 0.0;
  for (const auto& r : ra) {
    ASSERT_FALSE(r[2].empty()) << "a row without S_raw at t = " << r[0];
    const double ti = std::stod(r[0]), v = std::stod(r[2]);
    if (!t.empty()) {  // the step ending at ti
      ASSERT_GT(ti, t.back());
      acc += (ti - t.back()) * v;
      acc_t += ti - t.back();
    }
    t.push_back(ti);
    raw.push_back(v);
    if (r[3].empty()) continue;
    const double mean = std::stod(r[3]);
    if (ti == 0.0) {
      EXPECT_EQ(mean, v);  // t = 0: both the instant's value
    } else {
      ASSERT_GT(acc_t, 0.0);
      EXPECT_NEAR(mean, acc / acc_t, 1e-6 * std::abs(mean) + 1e-3)
          << "interval (" << t_prev << ", " << ti << "]";
      ++means;
    }
    acc = acc_t = 0.0;
    t_prev = ti;
  }
  EXPECT_EQ(static_cast<long>(raw.size()), sum.steps + 1);  // t = 0 and every step
  EXPECT_EQ(means, 3);                                      // t = 0.01, 0.02, 0.03
  // The raw series moves within an interval (else the check above would be empty).
  EXPECT_GT(*std::max_element(raw.begin(), raw.end()) - *std::min_element(raw.begin(), raw.end()),
            10.0);
}

TEST(Probe, ReproducesTheInRunGauge) {
  const fs::path d = fresh_dir("probe");
  run(case_text(0.05), d, false, 2);
  std::ostringstream csv;
  ProbeOptions opt;
  opt.out_dir = d.string();
  opt.at = Eigen::Vector3d(0.0, 0.01, 0.0);
  opt.normal = Eigen::Vector3d(1.0, 0.0, 0.0);
  const int rows = run_probe(opt, csv);
  EXPECT_EQ(rows, 6);  // t = 0, 0.01, ..., 0.05

  // Same times and values as the P0 column written during the run.
  auto data_rows = [](const std::string& text) {
    std::vector<std::pair<double, double>> r;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || line[0] == 't') continue;
      double t, p;
      char c;
      std::istringstream(line) >> t >> c >> p;
      r.emplace_back(t, p);
    }
    return r;
  };
  const auto in_run = data_rows(read_text(d / "gauges_pressure.csv"));
  const auto post = data_rows(csv.str());
  ASSERT_EQ(in_run.size(), post.size());
  for (std::size_t i = 0; i < post.size(); ++i) {
    EXPECT_EQ(in_run[i].first, post[i].first);
    EXPECT_EQ(in_run[i].second, post[i].second) << "at t = " << post[i].first;
  }
  // The wall probe sees the column's pressure at the start (rho0 g (2a - 0.01) ~ 1 kPa).
  EXPECT_GT(post.front().second, 500.0);

  // A sensor face (--size, as a case gauge's `size`): at each snapshot, the face average of
  // the run's own function (solver/gauges.hpp face_pressure) on that snapshot's particles,
  // walls included (they enter the face's wetness).
  opt.size = 0.02;
  std::ostringstream face_csv;
  ASSERT_EQ(run_probe(opt, face_csv), 6);
  const auto faces = data_rows(face_csv.str());
  const std::string path = (d / "restart_case.h5").string();
  const RunMetadata m = read_metadata(path);
  const auto snaps = list_snapshots(path);
  ASSERT_EQ(faces.size(), snaps.size());
  for (std::size_t k = 0; k < snaps.size(); ++k) {
    const auto s = read_snapshot<2>(path, snaps[k]);
    ParticleSet<2> ps;
    for (std::size_t i = 0; i < s.pos.size(); ++i)
      ps.add(s.pos[i], s.vel[i], s.rho[i], s.mass[i], static_cast<Role>(s.type[i]), s.body[i]);
    const Vec<2> n(1.0, 0.0), c(0.0, 0.01), g(0.0, -9.81);
    std::vector<std::uint32_t> scratch;
    const double expect = with_kernel<2>(kernel_from_name(m.kernel), m.h, [&](const auto& kernel) {
      return face_pressure(ps, s.p, kernel, face_points<2>(c, n, 0.02, m.dp), n, m.h, m.rho0, g,
                           scratch);
    });
    EXPECT_EQ(faces[k].first, post[k].first);
    EXPECT_NEAR(faces[k].second, expect, 1e-8 * std::abs(expect) + 1e-9) << "at t = " << s.time;
  }
  EXPECT_GT(faces.front().second, 500.0);
  opt.normal.reset();  // a face needs its normal
  EXPECT_THROW(run_probe(opt, face_csv), std::invalid_argument);
}

TEST(Hdf5Layout, RunFileHoldsSnapshotsAndMetadata) {
  const fs::path d = fresh_dir("layout");
  run(case_text(0.02), d, false, 2);
  const std::string path = (d / "restart_case.h5").string();
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_GT(H5Lexists(f, "/metadata", H5P_DEFAULT), 0);
  const auto snaps = list_snapshots(path);
  ASSERT_EQ(snaps.size(), 3u);
  for (const char* name : {"pos", "vel", "rho", "p", "type", "body", "id", "mass"}) {
    const std::string ds = snaps.back().group + "/" + name;
    EXPECT_GT(H5Lexists(f, ds.c_str(), H5P_DEFAULT), 0) << ds;
  }
  H5Fclose(f);
  const RunMetadata m = read_metadata(path);
  EXPECT_EQ(m.case_name, "restart_case");
  EXPECT_EQ(m.dim, 2);
  EXPECT_NE(m.case_text.find("gauges:"), std::string::npos);
  const auto s = read_snapshot<2>(path, snaps.back());
  EXPECT_EQ(s.pos.size(), m.n_fluid + m.n_boundary);
}

}  // namespace
}  // namespace swell
