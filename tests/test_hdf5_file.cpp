// HDF5 run files and checkpoints: round trips through the public readers, the file layout
// checked with raw HDF5 calls, restart bookkeeping and crash recovery of checkpoints.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>

#include "io/hdf5_file.hpp"
#include "swell/version.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class Hdf5Test : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("swell_hdf5_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// Random particles in a shuffled order, with the last `excluded` moved past size() as the
// neighbour sort does; one excluded particle is non-finite, like a blown-up particle.
template <int D>
ParticleSet<D> random_particles(std::size_t n, std::size_t excluded, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto vec = [&] {
    Vec<D> v;
    for (int d = 0; d < D; ++d) v[d] = u(rng);
    return v;
  };
  ParticleSet<D> ps;
  for (std::size_t i = 0; i < n; ++i) {
    ps.add(vec(), vec(), 1000.0 + 10.0 * u(rng), 0.5 + 0.1 * u(rng),
           i % 3 == 0 ? Role::FixedWall : Role::Fluid, static_cast<std::uint16_t>(i % 4));
  }
  // Integrator memory differs from the current state, as in the middle of a step.
  for (std::size_t i = 0; i < n; ++i) {
    ps.vel_prev[i] = narrow<D>(vec());
    ps.rho_prev[i] = 1000.0 + u(rng);
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), rng);
  ps.permute(order);
  ps.n_active = n - excluded;
  if (excluded > 0) ps.pos[n - 1][0] = std::numeric_limits<double>::quiet_NaN();
  return ps;
}

std::vector<double> random_pressure(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-100.0, 1e4);
  std::vector<double> p(n);
  for (auto& x : p) x = u(rng);
  return p;
}

RunMetadata sample_metadata(int dim) {
  RunMetadata m;
  m.case_name = "dam break";
  m.case_file = "cases/dambreak.yaml";
  m.case_text = "# Dam break — Ω ≈ 1.0\nname: dam break\n  dp: 0.01\n\ttab\n";
  m.dim = dim;
  m.dp = 0.01;
  m.h = 0.013;
  m.c0 = 35.5;
  m.rho0 = 1000.0;
  m.kernel = "wendland";
  m.n_fluid = 1234;
  m.n_boundary = 567;
  m.body_names = {"tank", "gate ü", "obstacle"};
  return m;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// The first `n` entries of `v`, where v holds the whole storage.
template <class T>
std::vector<T> head(const std::vector<T>& v, std::size_t n) {
  return std::vector<T>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
}

// The first `n` stored velocities or densities in double.
template <int D>
std::vector<Vec<D>> widened(const std::vector<StateVec<D>>& v, std::size_t n) {
  std::vector<Vec<D>> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = widen<D>(v[i]);
  return out;
}
std::vector<double> widened(const std::vector<StateReal>& v, std::size_t n) {
  return std::vector<double>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
}

template <int D>
void expect_snapshot_matches(const SnapshotData<D>& s, const ParticleSet<D>& ps,
                             const std::vector<double>& p) {
  const std::size_t n = ps.size();
  EXPECT_TRUE(same_bits(s.pos, head(ps.pos, n)));
  // velocity and density: the stored values (float unless SWELL_DOUBLE_STATE), widened exactly
  EXPECT_TRUE(same_bits(s.vel, widened(ps.vel, n)));
  EXPECT_TRUE(same_bits(s.rho, widened(ps.rho, n)));
  EXPECT_TRUE(same_bits(s.p, head(p, n)));
  EXPECT_TRUE(same_bits(s.mass, head(ps.mass, n)));
  EXPECT_TRUE(same_bits(s.body, head(ps.body, n)));
  EXPECT_TRUE(same_bits(s.id, head(ps.id, n)));
  ASSERT_EQ(s.type.size(), n);
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(s.type[i], static_cast<std::uint8_t>(ps.role[i]));
}

template <int D>
void snapshot_round_trip(const std::string& path, std::size_t n, std::size_t excluded) {
  const auto ps = random_particles<D>(n, excluded, 7);
  const auto p = random_pressure(n, 8);  // as long as the storage; only size() are written
  {
    auto run = Hdf5RunFile::create(path, sample_metadata(D));
    run.write_snapshot<D>(0, 0.0, ps, p);
    run.write_snapshot<D>(42, 0.125, ps, p);
  }
  const auto list = list_snapshots(path);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[1].group, "/particles/0000000042");
  EXPECT_EQ(list[1].step, 42);
  EXPECT_EQ(list[1].time, 0.125);
  const auto s = read_snapshot<D>(path, list[1]);
  EXPECT_EQ(s.step, 42);
  EXPECT_EQ(s.time, 0.125);
  ASSERT_EQ(s.pos.size(), n - excluded);
  expect_snapshot_matches(s, ps, p);
}

TEST_F(Hdf5Test, SnapshotRoundTrip2D) {
  snapshot_round_trip<2>(file("run2.h5"), 3000, 25);
}

// Large enough that every array is chunked and compressed.
TEST_F(Hdf5Test, SnapshotRoundTrip3D) {
  snapshot_round_trip<3>(file("run3.h5"), 5000, 40);
}

TEST_F(Hdf5Test, SnapshotLayoutReadWithRawHdf5) {
  const std::string path = file("raw.h5");
  const auto ps = random_particles<3>(200, 10, 3);
  const auto p = random_pressure(200, 4);
  Hdf5RunFile::create(path, sample_metadata(3)).write_snapshot<3>(42, 0.5, ps, p);

  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t ds = H5Dopen2(f, "/particles/0000000042/pos", H5P_DEFAULT);
  ASSERT_GE(ds, 0);
  const hid_t space = H5Dget_space(ds);
  ASSERT_EQ(H5Sget_simple_extent_ndims(space), 2);
  hsize_t dims[2];
  H5Sget_simple_extent_dims(space, dims, nullptr);
  EXPECT_EQ(dims[0], 190u);
  EXPECT_EQ(dims[1], 3u);
  std::vector<double> raw(190 * 3);
  ASSERT_GE(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()), 0);
  for (std::size_t i = 0; i < 190; ++i)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(raw[i * 3 + d], ps.pos[i][d]);
  H5Sclose(space);
  H5Dclose(ds);

  const hid_t type_ds = H5Dopen2(f, "/particles/0000000042/type", H5P_DEFAULT);
  const hid_t stored = H5Dget_type(type_ds);
  EXPECT_EQ(H5Tget_class(stored), H5T_INTEGER);
  EXPECT_EQ(H5Tget_size(stored), 1u);
  EXPECT_EQ(H5Tget_sign(stored), H5T_SGN_NONE);
  H5Tclose(stored);
  H5Dclose(type_ds);

  const hid_t g = H5Gopen2(f, "/particles/0000000042", H5P_DEFAULT);
  double time = 0;
  const hid_t a_time = H5Aopen(g, "time", H5P_DEFAULT);
  ASSERT_GE(H5Aread(a_time, H5T_NATIVE_DOUBLE, &time), 0);
  EXPECT_EQ(time, 0.5);
  std::int64_t step = 0;
  const hid_t a_step = H5Aopen(g, "step", H5P_DEFAULT);
  const hid_t step_type = H5Aget_type(a_step);
  EXPECT_EQ(H5Tget_size(step_type), 8u);
  ASSERT_GE(H5Aread(a_step, H5T_NATIVE_INT64, &step), 0);
  EXPECT_EQ(step, 42);
  H5Tclose(step_type);
  H5Aclose(a_step);
  H5Aclose(a_time);
  H5Gclose(g);
  H5Fclose(f);
}

TEST_F(Hdf5Test, EmptySnapshot) {
  const std::string path = file("empty.h5");
  auto ps = random_particles<2>(10, 0, 1);
  ps.n_active = 0;
  Hdf5RunFile::create(path, sample_metadata(2)).write_snapshot<2>(5, 1.0, ps, {});
  const auto list = list_snapshots(path);
  ASSERT_EQ(list.size(), 1u);
  const auto s = read_snapshot<2>(path, list[0]);
  EXPECT_TRUE(s.pos.empty());
  EXPECT_TRUE(s.id.empty());
}

TEST_F(Hdf5Test, MetadataRoundTrip) {
  const std::string path = file("meta.h5");
  const auto m = sample_metadata(3);
  Hdf5RunFile::create(path, m);
  const auto r = read_metadata(path);
  EXPECT_EQ(r.case_name, m.case_name);
  EXPECT_EQ(r.case_file, m.case_file);
  EXPECT_EQ(r.case_text, m.case_text);
  EXPECT_EQ(r.version, SWELL_VERSION);  // swell/version.hpp, from CMakeLists.txt
  EXPECT_EQ(r.dim, 3);
  EXPECT_EQ(r.dp, m.dp);
  EXPECT_EQ(r.h, m.h);
  EXPECT_EQ(r.c0, m.c0);
  EXPECT_EQ(r.rho0, m.rho0);
  EXPECT_EQ(r.kernel, m.kernel);
  EXPECT_EQ(r.n_fluid, m.n_fluid);
  EXPECT_EQ(r.n_boundary, m.n_boundary);
  EXPECT_EQ(r.body_names, m.body_names);

  RunMetadata bare;  // empty strings and no bodies
  Hdf5RunFile::create(path, bare);
  const auto rb = read_metadata(path);
  EXPECT_TRUE(rb.case_text.empty());
  EXPECT_TRUE(rb.kernel.empty());
  EXPECT_TRUE(rb.body_names.empty());
}

TEST_F(Hdf5Test, OpenForAppendDropsLaterSnapshots) {
  const std::string path = file("append.h5");
  const auto ps = random_particles<2>(50, 5, 2);
  const auto p = random_pressure(50, 3);
  {
    auto run = Hdf5RunFile::create(path, sample_metadata(2));
    for (int k = 0; k < 4; ++k) run.write_snapshot<2>(10 * k, 0.1 * k, ps, p);
  }
  {
    auto run = Hdf5RunFile::open_for_append(path, sample_metadata(2), 0.1);
    EXPECT_EQ(run.snapshot_count(), 2u);
    run.write_snapshot<2>(15, 0.14, ps, p);
    run.write_snapshot<2>(15, 0.15, ps, p);  // the same step again replaces it
  }
  const auto list = list_snapshots(path);
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].step, 0);
  EXPECT_EQ(list[1].step, 10);
  EXPECT_EQ(list[2].step, 15);
  EXPECT_EQ(list[2].time, 0.15);
  EXPECT_EQ(read_metadata(path).case_text, sample_metadata(2).case_text);
}

// Each snapshot is its own file; the run file only links them. A restart rebuilds the links
// from the snapshot files, so a run file destroyed by a crash loses nothing.
TEST_F(Hdf5Test, SnapshotsAreFilesOfTheirOwnLinkedFromTheRunFile) {
  const std::string path = file("run.h5");
  const auto ps = random_particles<2>(40, 2, 5);
  const auto p = random_pressure(40, 6);
  {
    auto run = Hdf5RunFile::create(path, sample_metadata(2));
    for (int k = 0; k < 4; ++k) run.write_snapshot<2>(10 * k, 0.1 * k, ps, p);
  }
  const fs::path snaps = dir_ / "snapshots";
  ASSERT_TRUE(fs::exists(snaps / "run_0000000030.h5"));
  // A snapshot file reads on its own like a run file of one snapshot.
  const auto own = list_snapshots((snaps / "run_0000000020.h5").string());
  ASSERT_EQ(own.size(), 1u);
  EXPECT_EQ(own[0].step, 20);
  EXPECT_EQ(read_metadata((snaps / "run_0000000020.h5").string()).case_name, "dam break");
  // The run file holds external links, not copies.
  {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    H5L_info_t info;
    ASSERT_GE(H5Lget_info(f, "/particles/0000000010", &info, H5P_DEFAULT), 0);
    EXPECT_EQ(info.type, H5L_TYPE_EXTERNAL);
    H5Fclose(f);
  }
  // The run file destroyed (as by a kill in the middle of an in-place write), a leftover
  // temporary snapshot and a later snapshot: the restart at t = 0.2 keeps 0, 10, 20 exactly.
  { std::ofstream(path, std::ios::trunc) << "cut short"; }
  { std::ofstream(snaps / "run_0000000040.h5.tmp") << "half a snapshot"; }
  {
    auto run = Hdf5RunFile::open_for_append(path, sample_metadata(2), 0.2);
    EXPECT_EQ(run.snapshot_count(), 3u);
  }
  const auto list = list_snapshots(path);
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[2].step, 20);
  const auto s = read_snapshot<2>(path, list[2]);
  EXPECT_EQ(s.time, 0.2);
  expect_snapshot_matches(s, ps, p);
  EXPECT_FALSE(fs::exists(snaps / "run_0000000030.h5"));
  EXPECT_FALSE(fs::exists(snaps / "run_0000000040.h5.tmp"));
  EXPECT_FALSE(fs::exists(dir_ / "run.h5.tmp"));
  // A new run file of the same name starts without the old snapshots.
  Hdf5RunFile::create(path, sample_metadata(2));
  EXPECT_TRUE(list_snapshots(path).empty());
  EXPECT_FALSE(fs::exists(snaps / "run_0000000000.h5"));
}

TEST_F(Hdf5Test, OpenForAppendRejectsOtherDimension) {
  const std::string path = file("dim.h5");
  const auto ps = random_particles<2>(20, 0, 1);
  Hdf5RunFile::create(path, sample_metadata(2))
      .write_snapshot<2>(1, 0.0, ps, random_pressure(20, 2));
  EXPECT_THROW(Hdf5RunFile::open_for_append(path, sample_metadata(3), 0.0), std::runtime_error);
  EXPECT_EQ(list_snapshots(path).size(), 1u);
}

SimulationClock sample_clock(double t) {
  SimulationClock c;
  c.time = t;
  c.steps = 123456789012L;
  c.dt = 1.0 / 3.0 * 1e-4;
  c.first_dt = std::nextafter(2e-5, 1.0);
  c.verlet_counter = 37;
  c.excluded.out_of_domain = 3;
  c.excluded.non_finite = 1;
  c.excluded.density_out_of_range = 2;
  return c;
}

const std::map<std::string, double> kSchedule = {
    {"output", 0.05}, {"gauge:probe 1", 0.0125}, {"", -1.0}, {"checkpoint", 1.0 / 7.0}};

template <int D>
void expect_same_checkpoint(const Checkpoint<D>& c, const ParticleSet<D>& ps,
                            const SimulationClock& clock) {
  const auto& r = c.particles;
  EXPECT_EQ(r.n_active, ps.n_active);
  EXPECT_EQ(r.total(), ps.total());
  EXPECT_TRUE(same_bits(r.pos, ps.pos));  // includes the NaN of the excluded particle
  EXPECT_TRUE(same_bits(r.vel, ps.vel));
  EXPECT_TRUE(same_bits(r.rho, ps.rho));
  EXPECT_TRUE(same_bits(r.vel_prev, ps.vel_prev));
  EXPECT_TRUE(same_bits(r.rho_prev, ps.rho_prev));
  EXPECT_TRUE(same_bits(r.mass, ps.mass));
  EXPECT_TRUE(same_bits(r.role, ps.role));
  EXPECT_TRUE(same_bits(r.body, ps.body));
  EXPECT_TRUE(same_bits(r.id, ps.id));
  EXPECT_EQ(std::memcmp(&c.clock.time, &clock.time, sizeof(double)), 0);
  EXPECT_EQ(c.clock.steps, clock.steps);
  EXPECT_EQ(std::memcmp(&c.clock.dt, &clock.dt, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&c.clock.first_dt, &clock.first_dt, sizeof(double)), 0);
  EXPECT_EQ(c.clock.verlet_counter, clock.verlet_counter);
  EXPECT_EQ(c.clock.excluded.out_of_domain, clock.excluded.out_of_domain);
  EXPECT_EQ(c.clock.excluded.non_finite, clock.excluded.non_finite);
  EXPECT_EQ(c.clock.excluded.density_out_of_range, clock.excluded.density_out_of_range);
}

template <int D>
void checkpoint_round_trip(const std::string& path) {
  const auto ps = random_particles<D>(777, 13, 11);
  const auto clock = sample_clock(0.3141592653589793);
  write_checkpoint<D>(path, ps, clock, kSchedule);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_EQ(checkpoint_dimension(path), D);
  const auto c = read_checkpoint<D>(path);
  expect_same_checkpoint(c, ps, clock);
  EXPECT_EQ(c.schedule, kSchedule);
}

TEST_F(Hdf5Test, CheckpointRoundTripIsBitwiseExact2D) {
  checkpoint_round_trip<2>(file("c2.h5"));
}
TEST_F(Hdf5Test, CheckpointRoundTripIsBitwiseExact3D) {
  checkpoint_round_trip<3>(file("c3.h5"));
}

// A restart on as many ranks as wrote the checkpoint: each rank reads only its rows (its
// active block, then its excluded block), exactly the particles the rank held, bit for bit.
TEST_F(Hdf5Test, CheckpointRowsOfOneRank) {
  const std::string path = file("rows.h5");
  const auto ps = random_particles<3>(300, 9, 31);  // 291 active, 9 excluded
  write_checkpoint<3>(path, ps, sample_clock(1.0), kSchedule);
  WriteShare w;
  w.active = {100, 120, 71};
  w.excluded = {4, 0, 5};
  std::size_t a0 = 0, e0 = 0;
  for (int r = 0; r < 3; ++r) {
    w.rank = r;
    const auto c = read_checkpoint<3>(path, &w);
    const auto ur = static_cast<std::size_t>(r);
    ASSERT_EQ(c.particles.size(), w.active[ur]);
    ASSERT_EQ(c.particles.total(), w.active[ur] + w.excluded[ur]);
    for (std::size_t k = 0; k < c.particles.total(); ++k) {
      const std::size_t i = k < w.active[ur] ? a0 + k : 291 + e0 + (k - w.active[ur]);
      EXPECT_EQ(c.particles.id[k], ps.id[i]) << r << " " << k;
      EXPECT_EQ(c.particles.vel_prev[k], ps.vel_prev[i]);
      EXPECT_EQ(c.particles.rho[k], ps.rho[i]);
      EXPECT_EQ(std::memcmp(c.particles.pos[k].data(), ps.pos[i].data(), sizeof(Vec<3>)), 0);
    }
    a0 += w.active[ur];
    e0 += w.excluded[ur];
  }
  // A record that does not add up to the file's counts is refused, naming the file.
  w.active = {100, 120, 70};
  try {
    read_checkpoint<3>(path, &w);
    FAIL() << "a wrong decomposition record was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("decomposition record"), std::string::npos) << e.what();
  }
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST_F(Hdf5Test, CrashDuringCheckpointFallsBackToPrevious) {
  const std::string path = file("ck.h5");
  const auto a = random_particles<2>(300, 7, 21);
  const auto b = random_particles<2>(300, 9, 22);
  const auto clock_a = sample_clock(1.0), clock_b = sample_clock(2.0);
  write_checkpoint<2>(path, a, clock_a, kSchedule);
  write_checkpoint<2>(path, b, clock_b, kSchedule);
  EXPECT_EQ(latest_valid_checkpoint(path), path);
  expect_same_checkpoint(read_checkpoint<2>(path + ".prev"), a, clock_a);

  // The run died while a third checkpoint was being written: a truncated .tmp, and `path`
  // itself damaged (truncated here, garbage below).
  const std::string good_b = read_bytes(path);
  write_bytes(path + ".tmp", good_b.substr(0, good_b.size() / 2));
  write_bytes(path, good_b.substr(0, good_b.size() / 2));
  EXPECT_THROW(read_checkpoint<2>(path), std::runtime_error);
  EXPECT_EQ(latest_valid_checkpoint(path), path + ".prev");
  write_bytes(path, "\x89HDF\r\n\x1a\n garbage after a crash");
  const std::string chosen = latest_valid_checkpoint(path);
  ASSERT_EQ(chosen, path + ".prev");
  const auto c = read_checkpoint<2>(chosen);
  expect_same_checkpoint(c, a, clock_a);
  EXPECT_EQ(c.schedule, kSchedule);

  // The next checkpoint replaces the damaged file and keeps the good one as .prev.
  write_checkpoint<2>(path, b, clock_b, kSchedule);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_EQ(latest_valid_checkpoint(path), path);
  expect_same_checkpoint(read_checkpoint<2>(path), b, clock_b);
  expect_same_checkpoint(read_checkpoint<2>(path + ".prev"), a, clock_a);

  // Both damaged: the error names both files.
  write_bytes(path, "garbage");
  write_bytes(path + ".prev", "");
  try {
    latest_valid_checkpoint(path);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("'" + path + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'" + path + ".prev'"), std::string::npos) << msg;
  }
}

TEST_F(Hdf5Test, IncompleteCheckpointIsRejected) {
  const std::string path = file("incomplete.h5");
  const auto ps = random_particles<3>(40, 0, 5);
  write_checkpoint<3>(path, ps, sample_clock(0.5), kSchedule);
  write_checkpoint<3>(path, ps, sample_clock(0.6), kSchedule);
  // Remove the completion mark, as if the writer stopped just before it.
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  ASSERT_GE(H5Adelete(f, "complete"), 0);
  H5Fclose(f);
  try {
    read_checkpoint<3>(path);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("incomplete"), std::string::npos) << msg;
  }
  EXPECT_EQ(latest_valid_checkpoint(path), path + ".prev");
  EXPECT_EQ(read_checkpoint<3>(path + ".prev").clock.time, 0.5);
}

TEST_F(Hdf5Test, CheckpointDimensionMismatchIsClear) {
  const std::string path = file("dim2.h5");
  write_checkpoint<2>(path, random_particles<2>(20, 2, 9), sample_clock(0.1), {});
  EXPECT_EQ(checkpoint_dimension(path), 2);
  try {
    read_checkpoint<3>(path);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("2D"), std::string::npos) << msg;
    EXPECT_NE(msg.find("3D"), std::string::npos) << msg;
  }
  EXPECT_TRUE(read_checkpoint<2>(path).schedule.empty());
}

TEST_F(Hdf5Test, MissingFilesNameThePath) {
  const std::string path = file("nothing.h5");
  for (auto fn : {+[](const std::string& p) { read_checkpoint<2>(p); },
                  +[](const std::string& p) { read_metadata(p); },
                  +[](const std::string& p) { list_snapshots(p); }}) {
    try {
      fn(path);
      FAIL() << "expected an exception";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace swell
