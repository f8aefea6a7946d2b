// Pressure sensor faces (pressure gauges with `size`): the face average of the fluid pressure
// extrapolated to the wall equals the exact wall pressure on a hand-made hydrostatic field (2D
// segment, 3D disc), dry parts of a face read 0, the written value is the dt-weighted mean over
// the sampling interval (never a point sample), and `size` needs `normal`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "case/reader.hpp"
#include "run/gauge_set.hpp"
#include "solver/gauges.hpp"
#include "solver/physics/kernels.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;
constexpr double kRho0 = 1000.0, kG = 9.81, kLevel = 0.2;

// Fluid on the lattice of [0, 0.2]^D below the level, at rest, p = rho0 g (level - z).
template <int D>
ParticleSet<D> hydrostatic_block(double dp, std::vector<double>& pressure) {
  ParticleSet<D> ps;
  const int n = static_cast<int>(std::lround(0.2 / dp));
  const int nz = D == 3 ? n : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Vec<D> x;
        x[0] = (i + 0.5) * dp;
        x[1] = (j + 0.5) * dp;
        if constexpr (D == 3) x[2] = (k + 0.5) * dp;
        ps.add(x, Vec<D>::Zero(), kRho0, kRho0 * std::pow(dp, D), Role::Fluid, 0);
        pressure.push_back(kRho0 * kG * (kLevel - x[D - 1]));
      }
  return ps;
}

template <int D>
void check_floor_sensor(double dp) {
  std::vector<double> p;
  const ParticleSet<D> ps = hydrostatic_block<D>(dp, p);
  const WendlandC2<D> kernel(std::sqrt(double(D)) * dp);
  Vec<D> c = Vec<D>::Constant(0.1), n = Vec<D>::Zero(), g = Vec<D>::Zero();
  c[D - 1] = 0.0;
  n[D - 1] = 1.0;
  g[D - 1] = -kG;
  // Offset 2.5 dp (2D) / 3.5 dp (3D), beyond the kernel support: the probe points sit on a
  // lattice row with their whole support in the fluid, where the Shepard interpolation of a
  // field linear in z is exact by symmetry; the hydrostatic correction then gives the wall value.
  const double off = (D == 2 ? 2.5 : 3.5) * dp;
  const auto pts = face_points<D>(c, n, 0.03, dp);
  EXPECT_GE(pts.size(), D == 2 ? 6u : 12u);
  std::vector<std::uint32_t> scratch;
  const double pw = face_pressure(ps, p, kernel, pts, n, off, kRho0, g, scratch);
  EXPECT_NEAR(pw, kRho0 * kG * kLevel, 1e-9 * kRho0 * kG * kLevel) << D << "D";
  // The same face above the water reads 0 (air), half out of it reads between.
  Vec<D> side_n = Vec<D>::Zero(), top = Vec<D>::Constant(0.1);
  side_n[0] = 1.0;
  top[0] = 0.0;
  top[D - 1] = 0.5;
  const auto dry = face_points<D>(top, side_n, 0.03, dp);
  EXPECT_EQ(face_pressure(ps, p, kernel, dry, side_n, off, kRho0, g, scratch), 0.0);
  top[D - 1] = kLevel;
  const auto half = face_points<D>(top, side_n, 0.1, dp);
  const double ph = face_pressure(ps, p, kernel, half, side_n, off, kRho0, g, scratch);
  EXPECT_GT(ph, 0.0);
  EXPECT_LT(ph, kRho0 * kG * 0.05);
}

TEST(SensorFace, HydrostaticWallPressureIsExact2D) {
  check_floor_sensor<2>(0.01);
}
TEST(SensorFace, HydrostaticWallPressureIsExact3D) {
  check_floor_sensor<3>(0.02);
}

// The face average of the plain Shepard ratio at the face's points (what a face read before
// the wetness weight): the reference the weighted reading is checked against.
template <int D, class K>
double plain_shepard_face(const ParticleSet<D>& ps, const std::vector<double>& p, const K& kernel,
                          const std::vector<Vec<D>>& pts, const Vec<D>& n, double off) {
  double sum = 0.0;
  for (const auto& x : pts) {
    const double v = probe_pressure(ps, p, kernel, Vec<D>(x + off * n));
    if (!std::isnan(v)) sum += v;
  }
  return sum / static_cast<double>(pts.size());
}

// Water below kLevel in the corner of a side wall (x < 0) and a floor (z < 0), three layers
// of wall particles each, the fluid lattice held `gap` off both walls (its first row's centre;
// dp/2 as filled, about 1.5 dp behind DBC walls after a surge); p = rho0 g (kLevel - z) in the
// fluid, and a wall pressure no reading may use (1e9 Pa).
template <int D>
ParticleSet<D> walled_block(double dp, double gap, std::vector<double>& pressure) {
  ParticleSet<D> ps;
  const int n = static_cast<int>(std::lround(0.25 / dp));
  const int nz = D == 3 ? n : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = -3; j < n; ++j)
      for (int i = -3; i < n; ++i) {
        Vec<D> x;
        const bool wall = i < 0 || j < 0;
        x[0] = i < 0 ? (i + 0.5) * dp : gap + i * dp;
        x[D - 1] = j < 0 ? (j + 0.5) * dp : gap + j * dp;
        if constexpr (D == 3) x[1] = (k + 0.5) * dp;
        if (!wall && x[D - 1] > kLevel) continue;
        ps.add(x, Vec<D>::Zero(), kRho0, kRho0 * std::pow(dp, D),
               wall ? Role::FixedWall : Role::Fluid, wall ? 1 : 0);
        pressure.push_back(wall ? 1e9 : kRho0 * kG * (kLevel - x[D - 1]));
      }
  return ps;
}

// A face on the side wall just above the water: the plain Shepard ratio carries the top row's
// pressure rho0 g dp/2 up to a kernel support above the surface; the face reads it faded by
// the wetness weight, falling with height to exactly 0 a support above the water. Faces under
// water read the plain ratio (w = 1), also in the floor corner and mid-depth with the fluid
// held 1.5 dp off both walls (DBC's gap); the walls' own pressure never enters.
template <int D>
void check_face_wetness(double dp) {
  const double h = std::sqrt(double(D)) * dp;
  const WendlandC2<D> kernel(h);
  Vec<D> n = Vec<D>::Zero(), g = Vec<D>::Zero(), c = Vec<D>::Constant(0.1);
  n[0] = 1.0;
  g[D - 1] = -kG;
  c[0] = 0.0;
  std::vector<std::uint32_t> scratch;
  {
    std::vector<double> p;
    const ParticleSet<D> ps = walled_block<D>(dp, 0.5 * dp, p);
    const double p_top = kRho0 * kG * 0.5 * dp;
    double previous = std::numeric_limits<double>::infinity();
    for (const double k : {0.25, 0.5, 1.0, 1.5}) {
      c[D - 1] = kLevel + k * h;
      const auto pts = face_points<D>(c, n, dp, dp);
      const double face = face_pressure(ps, p, kernel, pts, n, h, kRho0, g, scratch);
      const double plain = plain_shepard_face(ps, p, kernel, pts, n, h);
      EXPECT_GT(plain, 0.3 * p_top) << D << "D, " << k << " h above the water";
      EXPECT_GE(face, 0.0) << D << "D, " << k << " h";
      EXPECT_LT(face, (k < 0.5 ? 0.8 : 0.5) * plain) << D << "D, " << k << " h";
      EXPECT_LT(face, previous) << D << "D, " << k << " h";
      if (k >= 1.0) {
        EXPECT_LT(face, 0.1 * p_top) << D << "D, " << k << " h";
      }
      previous = face;
    }
    c[D - 1] = kLevel + 2.0 * h + dp;  // beyond the support of every face point
    EXPECT_EQ(face_pressure(ps, p, kernel, face_points<D>(c, n, dp, dp), n, h, kRho0, g, scratch),
              0.0);
  }
  for (const double gap : {0.5, 1.5}) {
    std::vector<double> p;
    const ParticleSet<D> ps = walled_block<D>(dp, gap * dp, p);
    for (const double z : {0.75 * dp, 0.1}) {  // in the floor corner (Lobovsky's face 1), mid-depth
      c[D - 1] = z;
      const auto pts = face_points<D>(c, n, 1.05 * dp, dp);
      const double face = face_pressure(ps, p, kernel, pts, n, h, kRho0, g, scratch);
      const double plain = plain_shepard_face(ps, p, kernel, pts, n, h);
      EXPECT_NEAR(face, plain, 1e-9 * plain) << D << "D, gap " << gap << " dp, z " << z;
      // The interpolation itself (not the weight) reads the wall value within 5 % where the
      // fluid reaches the walls; in DBC's corner gap it reads 4 % (2D) / 10 % (3D) low.
      if (gap < 1.0 || z > 0.05) {
        EXPECT_NEAR(face, kRho0 * kG * (kLevel - z), 0.05 * kRho0 * kG * (kLevel - z))
            << D << "D, gap " << gap << " dp, z " << z;
      }
    }
  }
}

TEST(SensorFace, PointsAboveTheWaterFadeToZero2D) {
  check_face_wetness<2>(0.01);
}
TEST(SensorFace, PointsAboveTheWaterFadeToZero3D) {
  check_face_wetness<3>(0.02);
}

// The written value is the mean of the per-step values weighted by dt over the interval, and
// the interval's state survives a checkpoint (schedule) round trip.
TEST(SensorFace, WritesTheIntervalMeanNotAPointSample) {
  const double dp = 0.01;
  std::vector<double> p0;
  const ParticleSet<2> ps = hydrostatic_block<2>(dp, p0);
  GaugeSpec g;
  g.name = "S";
  g.kind = GaugeSpec::Kind::Pressure;
  g.at = Eigen::Vector3d(0.1, 0.0, 0.0);
  g.normal = Eigen::Vector3d(0.0, 1.0, 0.0);
  g.offset = 2.5 * dp;
  g.size = 0.03;
  GaugeContext ctx;
  ctx.params.dp = dp;
  ctx.params.h = std::sqrt(2.0) * dp;
  ctx.params.rho0 = kRho0;
  ctx.params.gravity = Eigen::Vector3d(0.0, -kG, 0.0);
  const fs::path dir = fs::temp_directory_path() / "swell_test_sensor";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const double wall = kRho0 * kG * kLevel;
  {
    GaugeSet<2> set({g}, 0.1, ctx, dir.string(), "sensor", -1.0);
    ASSERT_TRUE(set.averages());
    set.sample(0.0, ps, p0, {});  // t = 0: the instant's value
    // Steps of 0.02, 0.03, 0.05 s with the whole field scaled by 1, 3, 2: the hydrostatic
    // correction is not scaled, so the face reads s (wall - c) + c, c = rho0 g 2.5 dp.
    const double c = kRho0 * kG * 2.5 * dp;
    const double dts[3] = {0.02, 0.03, 0.05}, scales[3] = {1.0, 3.0, 2.0};
    double t = 0.0, expect = 0.0;
    for (int k = 0; k < 3; ++k) {
      std::vector<double> pk(p0);
      for (auto& v : pk) v *= scales[k];
      if (k == 1) {  // a checkpoint in the middle of the interval
        std::map<std::string, double> sched;
        set.save_schedule(sched);
        EXPECT_EQ(sched.count("gauge_acc.S"), 1u);
        set.load_schedule(sched);
      }
      set.accumulate(dts[k], ps, pk);
      t += dts[k];
      expect += dts[k] * (scales[k] * (wall - c) + c);
    }
    expect /= t;
    set.sample(t, ps, p0, {});  // the instant's field would read `wall`
    set.flush();
    std::ifstream f(dir / "gauges_pressure.csv");
    std::string line, last;
    std::vector<std::string> rows;
    while (std::getline(f, line))
      if (!line.empty() && line[0] != '#') rows.push_back(line);
    ASSERT_EQ(rows.size(), 3u);  // header, t = 0, t = 0.1
    const double v0 = std::stod(rows[1].substr(rows[1].find(',') + 1));
    const double v1 = std::stod(rows[2].substr(rows[2].find(',') + 1));
    EXPECT_NEAR(v0, wall, 1e-6 * wall);
    EXPECT_NEAR(v1, expect, 1e-6 * wall);
    EXPECT_GT(std::abs(v1 - wall), 0.5 * wall);  // clearly not the instant's value
  }
}

TEST(SensorFace, SizeNeedsANormal) {
  const std::string text =
      "dim: 2\ndp: 0.01\ntime: {end: 0.1}\nbodies:\n"
      "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.4, 0.3]}}}\n"
      "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.4, 0.2]}}}\n"
      "gauges:\n  - {name: S, kind: pressure, at: [0.2, 0.0], size: 0.01}\n";
  try {
    parse_case_text(text, "s.yaml");
    FAIL() << "expected an error";
  } catch (const CaseError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("s.yaml:8"), std::string::npos) << m;
    EXPECT_NE(m.find("'size' (a sensor face) needs 'normal'"), std::string::npos) << m;
  }
  const std::string ok = text.substr(0, text.rfind("size")) + "normal: [0, 1], size: 0.01}\n";
  const CaseSpec spec = parse_case_text(ok, "s.yaml");
  ASSERT_EQ(spec.gauges.size(), 1u);
  EXPECT_EQ(*spec.gauges[0].size, 0.01);
}

}  // namespace
}  // namespace swell

namespace swell {
namespace {

// A jittered fluid block [0, 0.6] x [0, 0.12] (x [0, 0.1] in 3D) with random velocities and
// densities, above a floor of wall particles (body 1) with random accelerations.
template <int D>
ParticleSet<D> jittered_tank(double dp, std::vector<double>& p, std::vector<Vec<D>>& ace) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ParticleSet<D> ps;
  const int nx = 60, ny = D == 3 ? 10 : 1, nz = 12;
  for (int k = -3; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bool wall = k < 0;
        Vec<D> x;
        x[0] = (i + 0.5) * dp;
        if constexpr (D == 3) x[1] = (j + 0.5) * dp;
        x[D - 1] = (k + 0.5) * dp;
        Vec<D> v = Vec<D>::Zero();
        if (!wall)
          for (int d = 0; d < D; ++d) x[d] += 0.2 * dp * u(rng), v[d] = u(rng);
        const double rho = 1000.0 * (1.0 + 0.01 * u(rng));
        ps.add(x, v, rho, 1000.0 * std::pow(dp, D), wall ? Role::FixedWall : Role::Fluid,
               wall ? 1 : 0);
        p.push_back(1e3 * (1.0 + u(rng)));
        Vec<D> a;
        for (int d = 0; d < D; ++d) a[d] = u(rng);
        ace.push_back(a);
      }
  return ps;
}

template <int D>
void check_region(KernelType kernel) {
  const double dp = 0.01;
  std::vector<double> p;
  std::vector<Vec<D>> ace;
  const ParticleSet<D> ps = jittered_tank<D>(dp, p, ace);
  GaugeContext ctx;
  ctx.params.dp = dp;
  ctx.params.h = std::sqrt(double(D)) * dp;
  ctx.params.kernel = kernel;
  ctx.params.rho0 = 1000.0;
  ctx.params.gravity = Eigen::Vector3d::Zero();
  ctx.params.gravity[D - 1] = -9.81;
  ctx.up_axis = D - 1;
  ctx.floor = 0.0;
  ctx.line_top = 0.3;
  ctx.body_ids = {{"water", 0}, {"floor", 1}};
  auto at = [](double x, double z) {
    Eigen::Vector3d v(x, 0.05, 0.0);
    v[D - 1] = z;
    return v;
  };
  std::vector<GaugeSpec> gs;
  auto add = [&](GaugeSpec::Kind k, Eigen::Vector3d x) {
    GaugeSpec g;
    g.name = "G" + std::to_string(gs.size());
    g.kind = k;
    g.at = x;
    gs.push_back(g);
    return &gs.back();
  };
  add(GaugeSpec::Kind::Pressure, at(0.1, 0.05));
  add(GaugeSpec::Kind::Pressure, at(0.2, 0.0))->normal = at(0.0, 2.0);  // not a unit vector
  GaugeSpec* face = add(GaugeSpec::Kind::Pressure, at(0.15, 0.0));
  face->normal = Eigen::Vector3d::Unit(D - 1);
  face->size = 0.03;
  add(GaugeSpec::Kind::Velocity, at(0.05, 0.08));
  add(GaugeSpec::Kind::Height, at(0.12, 0.0));
  add(GaugeSpec::Kind::Height, at(0.22, 0.0))->level = GaugeSpec::Level::Integral;
  GaugeSpec* run = add(GaugeSpec::Kind::Runup, at(0.0, 0.0));
  run->from = at(0.22, 0.0);
  run->to = at(0.32, 0.2);
  add(GaugeSpec::Kind::Front, at(0.0, 0.0));
  add(GaugeSpec::Kind::Force, at(0.0, 0.0))->body = "floor";
  const GaugeRegion<D> region = gauge_region<D>(gs, ctx);
  // The particles in the region, in their order, with their pressures and accelerations.
  ParticleSet<D> near;
  std::vector<double> pn;
  std::vector<Vec<D>> an;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!region.contains(ps, i)) continue;
    near.add(ps.pos[i], ps.velocity(i), ps.rho[i], ps.mass[i], ps.role[i], ps.body[i]);
    pn.push_back(p[i]);
    an.push_back(ace[i]);
  }
  for (const auto& g : gs) {
    const auto all = evaluate_gauge<D>(g, ctx, ps, p, ace);
    const auto part = evaluate_gauge<D>(g, ctx, near, pn, an);
    ASSERT_EQ(all.size(), part.size());
    for (std::size_t k = 0; k < all.size(); ++k) {
      EXPECT_TRUE(std::isfinite(all[k])) << g.name;
      EXPECT_EQ(std::memcmp(&all[k], &part[k], sizeof(double)), 0)
          << D << "D " << g.name << "[" << k << "]: " << all[k] << " from every particle, "
          << part[k] << " from the region";
    }
  }
  // Without the front's band and the floor's body, the region is a small part of the tank.
  std::vector<GaugeSpec> points(gs.begin(), gs.begin() + 4);
  const GaugeRegion<D> small = gauge_region<D>(points, ctx);
  std::size_t inside = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) inside += small.contains(ps, i);
  EXPECT_LT(inside, ps.size() / 3);
  EXPECT_GT(inside, 0u);
}

// A decomposed run gathers only the particles in the gauges' region to rank 0 for its gauges:
// every gauge kind reads the same, bit for bit, from them as from the whole set.
TEST(GaugeRegion, GaugesReadTheSameFromTheRegionAlone) {
  check_region<2>(KernelType::Wendland);
  check_region<3>(KernelType::Wendland);
  check_region<2>(KernelType::Quintic);  // support 3h
}

}  // namespace
}  // namespace swell
