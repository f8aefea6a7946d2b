// Tests for bc/motion (prescribed rigid-body motion) and its case-file reader case/motion:
// velocities are the derivatives of the positions, each law matches its closed form, rotations
// are rigid and periodic, tables are interpolated to a stated accuracy, the motion is frozen
// after stop, swept bounds contain the motion, and case-file mistakes name file and line.
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "bc/motion.hpp"
#include "case/motion.hpp"
#include "case/reader.hpp"
#include "case/schema.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// A folder of its own for files written by the tests.
fs::path temp_dir() {
  static const fs::path dir = [] {
    const fs::path d =
        fs::temp_directory_path() / ("swell_test_motion_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path path = temp_dir() / name;
  std::ofstream(path) << text;
  return path;
}

// ---------------------------------------------------------------------------------------------
// Laws used by several tests; `kinks` are the times where the law is only C1 (or C0), which the
// finite-difference checks stay away from.

struct Law {
  std::string name;
  MotionSpec spec;
  std::vector<double> kinks;
};

using Type = MotionSpec::Type;

MotionSpec linear(double ramp) {
  return {.type = Type::Linear,
          .velocity = Vector3d(0.3, -0.1, 0.0),
          .acceleration = Vector3d(0.05, 0.02, 0.0),
          .start = 0.5,
          .stop = 3.0,
          .ramp = ramp};
}

MotionSpec sinusoid(double ramp) {  // the direction is normalised by MotionLaw
  return {.type = Type::Sinusoidal,
          .amplitude = 0.05,
          .period = 1.2,
          .phase = 0.4,
          .direction = Vector3d(1.0, 1.0, 0.0),
          .start = 0.2,
          .stop = 4.0,
          .ramp = ramp};
}

MotionSpec turning(double ramp) {  // constant rate
  return {.type = Type::Rotation,
          .centre = Vector3d(0.5, 0.1, 0.0),
          .rate = 30.0 * kDeg,
          .start = 0.1,
          .stop = 3.0,
          .ramp = ramp};
}

MotionSpec flap(double ramp) {  // sinusoidal rotation
  return {.type = Type::Rotation,
          .amplitude = 10.0 * kDeg,
          .period = 2.0,
          .phase = 0.3,
          .centre = Vector3d(0.5, 0.1, 0.0),
          .start = 0.1,
          .stop = 5.0,
          .ramp = ramp};
}

// A table sampled from a sinusoid of amplitude `a`, period 1.2, `per_period` samples per period
// over two periods.
void sample_sinusoid(MotionSpec& s, double a, int per_period) {
  for (int i = 0; i <= 2 * per_period; ++i) {
    const double t = 1.2 * i / per_period;
    s.series_t.push_back(t);
    s.series_value.push_back(a * std::sin(2.0 * kPi * t / 1.2));
  }
}

MotionSpec table(MotionSpec::Quantity quantity, double ramp) {
  MotionSpec s{.type = Type::File,
               .centre = Vector3d(0.5, 0.1, 0.0),
               .quantity = quantity,
               .start = 0.3,
               .stop = 2.5,
               .ramp = ramp};
  sample_sinusoid(s, quantity == MotionSpec::Quantity::Angle ? 0.2 : 0.05, 20);
  return s;
}

std::vector<Law> all_laws() {
  std::vector<Law> laws = {
      {"linear", linear(0.0), {}},
      {"linear_ramp", linear(0.2), {}},
      {"sinusoid", sinusoid(0.0), {}},
      {"sinusoid_ramp", sinusoid(0.5), {}},
      {"turning_ramp", turning(0.4), {}},
      {"flap_ramp", flap(0.5), {}},
      {"table", table(MotionSpec::Quantity::Displacement, 0.0), {}},
      {"table_angle_ramp", table(MotionSpec::Quantity::Angle, 0.3), {}},
  };
  MotionSpec tilted = flap(0.2);  // 3D: a tilted axis, off-plane centre
  tilted.axis = Vector3d(0.3, -0.5, 0.8);
  tilted.centre = Vector3d(0.5, 0.1, 0.2);
  laws.push_back({"flap_3d", tilted, {}});
  for (Law& law : laws) {
    const MotionSpec& s = law.spec;
    law.kinks = {s.start, s.start + s.ramp, s.stop};
    for (double t : s.series_t) law.kinks.push_back(s.start + t);
  }
  return laws;
}

// Reference points of a body: a few points around the centre, z = 0 unless `three_d`.
std::vector<Vector3d> body_points(bool three_d) {
  std::vector<Vector3d> points;
  for (int i = 0; i < 6; ++i) {
    points.emplace_back(0.3 + 0.07 * i, 0.05 + 0.03 * (i % 3), three_d ? 0.1 * (i % 2) : 0.0);
  }
  return points;
}

bool is_3d(const MotionSpec& s) {
  return s.axis.x() != 0.0 || s.axis.y() != 0.0;
}

// ---------------------------------------------------------------------------------------------
// Laws

// The analytic velocities are the central differences of the positions, to 1e-7 of the law's
// largest speed (step 1e-5 s: truncation ~1e-9, round-off ~1e-10 relative), at times before
// start, inside the ramp, after the ramp and after stop, skipping 3 steps around each kink.
TEST(MotionLaw, VelocityIsDerivativeOfPosition) {
  const double e = 1e-5;
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name);
    const MotionLaw m(law.spec);
    const auto points = body_points(is_3d(law.spec));
    std::vector<double> times;
    for (double t = -0.3; t < law.spec.stop + 0.5; t += 0.00737) {
      bool near_kink = false;
      for (double k : law.kinks) near_kink = near_kink || std::abs(t - k) < 3 * e;
      if (!near_kink) times.push_back(t);
    }
    double vmax = 0.0, wmax = 0.0, pmax = 0.0;
    Vector3d x, v, xp, xm, unused;
    for (double t : times) {
      const RigidPose p = m.pose(t);
      vmax = std::max(vmax, p.dv.norm());
      wmax = std::max(wmax, std::abs(p.omega));
      for (const Vector3d& r : points) {
        m.place(p, r, x, v);
        pmax = std::max(pmax, v.norm());
      }
    }
    ASSERT_GT(vmax + wmax, 0.0);
    int checked = 0;
    for (double t : times) {
      const RigidPose p = m.pose(t), pp = m.pose(t + e), pm = m.pose(t - e);
      const Vector3d fd = (pp.d - pm.d) / (2 * e);
      ASSERT_LE((fd - p.dv).norm(), 1e-7 * std::max(vmax, 1e-300)) << "t = " << t;
      ASSERT_LE(std::abs((pp.theta - pm.theta) / (2 * e) - p.omega), 1e-7 * std::max(wmax, 1e-300))
          << "t = " << t;
      for (const Vector3d& r : points) {  // the point velocities of place() too
        m.place(p, r, x, v);
        m.place(pp, r, xp, unused);
        m.place(pm, r, xm, unused);
        ASSERT_LE(((xp - xm) / (2 * e) - v).norm(), 1e-7 * pmax) << "t = " << t;
      }
      ++checked;
    }
    EXPECT_GT(checked, 400);
  }
}

TEST(MotionLaw, LinearWithoutRampIsExact) {
  const MotionSpec s = linear(0.0);
  const MotionLaw m(s);
  for (double tau : {0.0, 0.1, 0.77, 1.3, 2.49}) {  // stop at tau = 2.5
    const RigidPose p = m.pose(s.start + tau);
    const Vector3d d = s.velocity * tau + 0.5 * s.acceleration * tau * tau;
    const Vector3d dv = s.velocity + s.acceleration * tau;
    for (int a = 0; a < 3; ++a) {  // a few ulp
      EXPECT_NEAR(p.d[a], d[a], 4e-16 * (1.0 + std::abs(d[a]))) << "tau = " << tau;
      EXPECT_NEAR(p.dv[a], dv[a], 4e-16 * (1.0 + std::abs(dv[a]))) << "tau = " << tau;
    }
    EXPECT_EQ(p.theta, 0.0);
  }
}

// Simpson's rule of f over [a, b] with n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return sum * h / 3.0;
}

// The ramped displacement is the integral of the ramped velocity r(tau) (V + A tau), checked
// against Simpson's rule (1e-13 m; the integrand is a quartic on the ramp, so the rule's error
// is ~1e-16); position and velocity are continuous at tau = ramp (1e-8 across 2e-9 s), and the
// body starts from rest.
TEST(MotionLaw, LinearRampIsIntegralOfRampedVelocity) {
  const MotionSpec s = linear(0.2);
  const MotionLaw m(s);
  const double R = s.ramp;
  const auto ramp = [R](double u) {
    const double q = std::min(u / R, 1.0);
    return q * q * (3.0 - 2.0 * q);
  };
  for (double tau : {0.03, 0.1, 0.2, 0.35, 1.7}) {
    const RigidPose p = m.pose(s.start + tau);
    for (int a = 0; a < 2; ++a) {
      const auto f = [&](double u) { return ramp(u) * (s.velocity[a] + s.acceleration[a] * u); };
      const double d =
          simpson(f, 0.0, std::min(tau, R), 1000) + (tau > R ? simpson(f, R, tau, 1000) : 0.0);
      EXPECT_NEAR(p.d[a], d, 1e-13) << "tau = " << tau;
      EXPECT_NEAR(p.dv[a], f(tau), 1e-15) << "tau = " << tau;
    }
  }
  const RigidPose below = m.pose(s.start + R - 1e-9), above = m.pose(s.start + R + 1e-9);
  EXPECT_LE((above.dv - below.dv).norm(), 1e-8);
  EXPECT_LE((above.d - below.d).norm(), 1e-8);
  const RigidPose at_start = m.pose(s.start);
  EXPECT_EQ(at_start.dv, Vector3d::Zero());
  EXPECT_EQ(at_start.d, Vector3d::Zero());
}

// After a whole period a flap is back where it was, every point to 1e-12 m; so is a constant
// rate of 360 deg per period, and, with a ramp, 360 deg after period + ramp / 2 (the ramp costs
// half its duration at full rate).
TEST(MotionLaw, RotationReturnsAfterOnePeriod) {
  const auto expect_same = [](const MotionLaw& m, double t1, double t2) {
    Vector3d x1, x2, v;
    for (const Vector3d& r : body_points(false)) {
      m.place(m.pose(t1), r, x1, v);
      m.place(m.pose(t2), r, x2, v);
      EXPECT_LE((x1 - x2).norm(), 1e-12) << "t1 = " << t1 << ", t2 = " << t2;
    }
  };
  const MotionSpec f0 = flap(0.0);
  expect_same(MotionLaw(f0), f0.start, f0.start + f0.period);
  const MotionSpec f1 = flap(0.5);
  expect_same(MotionLaw(f1), f1.start + 0.7, f1.start + 0.7 + f1.period);

  MotionSpec turn = turning(0.0);
  const double period = 1.7;
  turn.rate = 2.0 * kPi / period;
  turn.stop = 10.0;
  expect_same(MotionLaw(turn), turn.start, turn.start + period);
  EXPECT_NEAR(MotionLaw(turn).pose(turn.start + period).theta, 2.0 * kPi, 1e-14);
  turn.ramp = 0.4;
  const MotionLaw ramped(turn);
  EXPECT_NEAR(ramped.pose(turn.start + period + 0.2).theta, 2.0 * kPi, 1e-14);
  expect_same(ramped, 0.0, turn.start + period + 0.2);
}

// place() is rigid: distances to the centre and between points are kept (1e-12 relative), the
// component along the axis is kept, and a 2D motion keeps z = 0 exactly.
TEST(MotionLaw, PlaceIsRigid) {
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name);
    const MotionLaw m(law.spec);
    const bool three_d = is_3d(law.spec);
    const auto refs = body_points(three_d);
    const Vector3d c = law.spec.centre, axis = law.spec.axis.normalized();
    for (double t = 0.0; t < law.spec.stop + 0.5; t += 0.0913) {
      const RigidPose p = m.pose(t);
      std::vector<Vector3d> xs(refs.size());
      Vector3d v;
      for (std::size_t i = 0; i < refs.size(); ++i) {
        m.place(p, refs[i], xs[i], v);
        const Vector3d r = xs[i] - c - p.d, r0 = refs[i] - c;
        EXPECT_NEAR(r.norm(), r0.norm(), 1e-12 * r0.norm());
        EXPECT_NEAR(r.dot(axis), r0.dot(axis), 1e-12 * r0.norm());
        if (!three_d) {
          EXPECT_EQ(xs[i].z(), 0.0);
          EXPECT_EQ(v.z(), 0.0);
        }
        for (std::size_t j = 0; j < i; ++j) {
          const double d0 = (refs[i] - refs[j]).norm();
          EXPECT_NEAR((xs[i] - xs[j]).norm(), d0, 1e-12 * d0);
        }
      }
    }
  }
}

// From stop on the pose is frozen (bitwise) at its value at stop, reached continuously, with
// velocities exactly 0; before start the pose is the law at tau = 0, at rest.
TEST(MotionLaw, FrozenAfterStopAndAtRestBeforeStart) {
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name);
    const MotionLaw m(law.spec);
    const double stop = law.spec.stop, start = law.spec.start;
    const RigidPose at = m.pose(stop), near = m.pose(stop - 1e-9);
    for (double t : {stop, stop + 0.5, stop + 1e3}) {
      const RigidPose p = m.pose(t);
      EXPECT_EQ(p.d, at.d);
      EXPECT_EQ(p.theta, at.theta);
      EXPECT_EQ(p.dv, Vector3d::Zero());
      EXPECT_EQ(p.omega, 0.0);
    }
    EXPECT_LE((at.d - near.d).norm(), 1e-8);
    EXPECT_LE(std::abs(at.theta - near.theta), 1e-8);
    EXPECT_TRUE(near.dv.norm() > 0.0 || near.omega != 0.0);  // it was moving
    const RigidPose zero = m.pose(start);
    for (double t : {start - 1e-9, start - 0.1, -5.0}) {
      const RigidPose p = m.pose(t);
      EXPECT_EQ(p.d, zero.d);
      EXPECT_EQ(p.theta, zero.theta);
      EXPECT_EQ(p.dv, Vector3d::Zero());
      EXPECT_EQ(p.omega, 0.0);
    }
  }
  const MotionLaw none;
  EXPECT_FALSE(none.moves());
  EXPECT_TRUE(MotionLaw(linear(0.0)).moves());
  EXPECT_EQ(none.pose(1.0).d, Vector3d::Zero());
}

TEST(MotionLaw, RejectsInvalidSpecs) {
  MotionSpec s = sinusoid(0.0);
  s.period = 0.0;
  EXPECT_THROW(MotionLaw{s}, std::invalid_argument);
  s = sinusoid(0.0);
  s.direction.setZero();
  EXPECT_THROW(MotionLaw{s}, std::invalid_argument);
  s = linear(-1.0);
  EXPECT_THROW(MotionLaw{s}, std::invalid_argument);
  s = linear(0.0);
  s.stop = s.start;
  EXPECT_THROW(MotionLaw{s}, std::invalid_argument);
  s = table(MotionSpec::Quantity::Displacement, 0.0);
  s.series_value.pop_back();
  EXPECT_THROW(MotionLaw{s}, std::invalid_argument);
  s = table(MotionSpec::Quantity::Displacement, 0.0);
  s.series_t[3] = s.series_t[2];
  EXPECT_THROW(MotionLaw{s}, std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Tables

// The spline reproduces quadratics exactly (three-point slopes, one-sided at the ends) on a
// non-uniform grid, and holds the end values with zero velocity outside the table.
TEST(MotionTable, ReproducesQuadraticsAndHoldsEnds) {
  MotionSpec s;
  s.type = MotionSpec::Type::File;
  s.series_t = {0.2, 0.3, 0.55, 0.6, 1.1, 1.2};
  const auto f = [](double t) { return 1.0 + 2.0 * t - 3.0 * t * t; };
  for (double t : s.series_t) s.series_value.push_back(f(t));
  const MotionLaw m(s);
  for (double tau = 0.2; tau < 1.2; tau += 0.0123) {
    const RigidPose p = m.pose(tau);
    EXPECT_NEAR(p.d.x(), f(tau), 1e-13) << tau;
    EXPECT_NEAR(p.dv.x(), 2.0 - 6.0 * tau, 1e-12) << tau;
    EXPECT_EQ(p.d.y(), 0.0);
  }
  for (double tau : {0.0, 0.1, 0.1999}) {
    EXPECT_EQ(m.pose(tau).d.x(), f(0.2));
    EXPECT_EQ(m.pose(tau).dv.x(), 0.0);
  }
  for (double tau : {1.2, 1.5, 9.0}) {
    EXPECT_EQ(m.pose(tau).d.x(), f(1.2));
    EXPECT_EQ(m.pose(tau).dv.x(), 0.0);
  }
}

// A CSV sampled 200 times per period from d = A sin(2 pi t / P) (A = 0.05 m, P = 1.2 s) gives
// back d to 5e-6 A and its velocity to 1e-3 A omega over both periods (measured: 2.0e-6 A and
// 3.1e-4 A omega, at the one-sided end slopes), and to 1e-6 A and 3e-4 A omega away from the
// ends (measured 5.0e-7 A and 1.6e-4 A omega: errors O(h^3) and O(h^2) of the knot slopes).
TEST(MotionTable, CsvOfSinusoidMatchesAnalytic) {
  const double A = 0.05, P = 1.2, w = 2.0 * kPi / P;
  std::ostringstream csv;
  csv.precision(17);
  csv << "# piston stroke sampled from a sinusoid\nt,x\n";
  for (int i = 0; i <= 400; ++i) csv << P * i / 200 << "," << A * std::sin(w * P * i / 200) << "\n";
  const fs::path path = write_file("sinusoid.csv", csv.str());
  const MotionSeries series = load_motion_csv(path.string(), MotionSpec::Quantity::Displacement);
  ASSERT_EQ(series.t.size(), 401u);
  MotionSpec s;
  s.type = MotionSpec::Type::File;
  s.start = 0.3;
  s.series_t = series.t;
  s.series_value = series.value;
  const MotionLaw m(s);
  double d_err = 0.0, v_err = 0.0, d_mid = 0.0, v_mid = 0.0;
  for (int k = 1; k < 20000; ++k) {
    const double tau = 2.0 * P * k / 20000;
    const RigidPose p = m.pose(s.start + tau);
    const double de = std::abs(p.d.x() - A * std::sin(w * tau));
    const double ve = std::abs(p.dv.x() - A * w * std::cos(w * tau));
    d_err = std::max(d_err, de);
    v_err = std::max(v_err, ve);
    if (tau > 0.1 && tau < 2.0 * P - 0.1) {
      d_mid = std::max(d_mid, de);
      v_mid = std::max(v_mid, ve);
    }
  }
  EXPECT_LT(d_err, 5e-6 * A);
  EXPECT_LT(v_err, 1e-3 * A * w);
  EXPECT_LT(d_mid, 1e-6 * A);
  EXPECT_LT(v_mid, 3e-4 * A * w);
  EXPECT_GT(v_err, 0.0);  // a tolerance the interpolant uses, not an exact reproduction

  const MotionSeries angle = load_motion_csv(path.string(), MotionSpec::Quantity::Angle);
  EXPECT_DOUBLE_EQ(angle.value[50], series.value[50] * kDeg);  // degrees in the file
}

TEST(MotionTable, CsvFormat) {
  // Comments, blank lines, CRLF and a '+' sign are accepted; a first line of numbers is data.
  const fs::path ok = write_file("ok.csv", "# c\r\n\r\ntime , angle\r\n0, +1\r\n# c\r\n0.5,2\r\n");
  const MotionSeries s = load_motion_csv(ok.string(), MotionSpec::Quantity::Displacement);
  EXPECT_EQ(s.t, (std::vector<double>{0.0, 0.5}));
  EXPECT_EQ(s.value, (std::vector<double>{1.0, 2.0}));
  const fs::path bare = write_file("bare.csv", "0,0\n1,1\n");
  EXPECT_EQ(load_motion_csv(bare.string(), MotionSpec::Quantity::Displacement).t.size(), 2u);
#ifdef SWELL_SOURCE_DIR
  const MotionSeries flap_file = load_motion_csv(
      std::string(SWELL_SOURCE_DIR) + "/tests/data/motion_flap.csv", MotionSpec::Quantity::Angle);
  ASSERT_EQ(flap_file.t.size(), 6u);
  EXPECT_DOUBLE_EQ(flap_file.value[3], 8.0 * kDeg);
#endif
}

// `column:` picks the value column of a wider record by its header name (t is the first).
TEST(MotionTable, NamedColumnOfAWiderRecord) {
  const fs::path wide = write_file(
      "wide.csv", "# rec\nt_s, x_m, u_mps, eta\n0, 0.0, 9, 1\n0.5, 0.25, 9, 2\n1, 1, 9, 3\n");
  const MotionSeries s = load_motion_csv(wide.string(), MotionSpec::Quantity::Displacement, "x_m");
  EXPECT_EQ(s.t, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(s.value, (std::vector<double>{0.0, 0.25, 1.0}));
  const MotionSeries e = load_motion_csv(wide.string(), MotionSpec::Quantity::Angle, "eta");
  EXPECT_DOUBLE_EQ(e.value[2], 3.0 * kDeg);
  const auto message = [&](const fs::path& f, const std::string& column) -> std::string {
    try {
      load_motion_csv(f.string(), MotionSpec::Quantity::Displacement, column);
    } catch (const std::invalid_argument& err) {
      return err.what();
    }
    return "no error";
  };
  EXPECT_NE(message(wide, "x").find("wide.csv:2: no value column 'x' in the header"),
            std::string::npos);
  EXPECT_NE(message(wide, "x").find("x_m, u_mps, eta"), std::string::npos);
  EXPECT_NE(message(wide, "t_s").find("no value column"), std::string::npos);  // t is not a value
  const fs::path short_row = write_file("short.csv", "t,a,b\n0,1,2\n1,1\n");
  EXPECT_NE(message(short_row, "b")
                .find("short.csv:3: expected numbers in column 1 (t) and "
                      "column 3 (b)"),
            std::string::npos);
}

TEST(MotionTable, CsvErrorsNameFileAndLine) {
  struct Bad {
    std::string text;
    std::string where;  // expected "<file>:<line>:" suffix of the path, or "<file>:"
    std::string what;
  };
  const std::vector<Bad> bad = {
      {"t,x\n0,0\n0.1,abc\n", ":3: ", "expected 2 numbers (t, value), got '0.1,abc'"},
      {"# c\nt,x\n# c\n0,0\n0.2\n", ":5: ", "expected 2 numbers (t, value), got '0.2'"},
      {"t,x\n0,1,2\n1,1\n", ":2: ", "expected 2 numbers"},
      {"t,x\n0,nan\n1,1\n", ":2: ", "expected 2 numbers"},
      {"t,x\n0,0\n0.5,1\n0.5,2\n", ":4: ", "times must increase strictly, but t = 0.5 follows"},
      {"t,x\n0,0\n0.5,1\n0.4,2\n", ":4: ", "(line 3)"},
      {"t,x\n0,0\n", ": ", "expected at least 2 data rows (t, value) after the header, found 1"},
      {"", ": ", "found 0"},
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    const std::string name = "bad" + std::to_string(i) + ".csv";
    const fs::path path = write_file(name, bad[i].text);
    try {
      load_motion_csv(path.string(), MotionSpec::Quantity::Displacement);
      ADD_FAILURE() << name << ": no error";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path.string() + bad[i].where, 0), 0u) << what;
      EXPECT_NE(what.find(bad[i].what), std::string::npos) << what;
    }
  }
  const std::string missing = (temp_dir() / "missing.csv").string();
  try {
    load_motion_csv(missing, MotionSpec::Quantity::Angle);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": cannot open the motion time series for reading");
  }
}

// ---------------------------------------------------------------------------------------------
// Swept bounds

// The swept box contains every point of the body (corners and interior) at 40000 times, exactly,
// and exceeds their extent by at most 3 % of it; 2D boxes keep z = 0.
TEST(MotionBounds, SweepContainsEveryPose) {
  std::vector<Law> laws = all_laws();
  MotionSpec fast = sinusoid(0.0);  // 200 cycles: more than 256 samples are needed
  fast.period = 0.05;
  fast.stop = 12.0;
  laws.push_back({"fast_sinusoid", fast, {}});
  laws.push_back({"none", MotionSpec{}, {}});
  for (const Law& law : laws) {
    SCOPED_TRACE(law.name);
    const MotionLaw m(law.spec);
    const bool three_d = is_3d(law.spec);
    const Vector3d box_lo(0.4, 0.0, 0.0), box_hi(0.6, 0.2, three_d ? 0.1 : 0.0);
    const auto corners = box_corners(box_lo, box_hi);
    const double t_long = std::min(law.spec.stop + 1.0, 20.0);
    for (double t_end : {law.spec.start + 0.5 * law.spec.ramp + 0.3, t_long}) {
      Vector3d lo, hi;
      sweep_bounds(m, t_end, corners, lo, hi);
      Vector3d seen_lo = box_lo, seen_hi = box_hi, x, v;
      for (int k = 0; k <= 40000; ++k) {
        const RigidPose p = m.pose(t_end * k / 40000);
        for (int c = 0; c < 27; ++c) {  // corners, edge midpoints, face centres, the middle
          const Vector3d q(c % 3 / 2.0, c / 3 % 3 / 2.0, c / 9 / 2.0);
          m.place(p, box_lo + q.cwiseProduct(box_hi - box_lo), x, v);
          seen_lo = seen_lo.cwiseMin(x);
          seen_hi = seen_hi.cwiseMax(x);
        }
      }
      for (int a = 0; a < 3; ++a) {
        EXPECT_LE(lo[a], seen_lo[a]) << "axis " << a << ", t_end " << t_end;
        EXPECT_GE(hi[a], seen_hi[a]) << "axis " << a << ", t_end " << t_end;
        const double extent = (seen_hi - seen_lo).maxCoeff();
        EXPECT_LE(seen_lo[a] - lo[a], 0.03 * extent) << "axis " << a;
        EXPECT_LE(hi[a] - seen_hi[a], 0.03 * extent) << "axis " << a;
      }
      if (!three_d) {
        EXPECT_EQ(lo.z(), 0.0);
        EXPECT_EQ(hi.z(), 0.0);
      }
    }
  }
  Vector3d lo, hi;
  EXPECT_THROW(sweep_bounds(MotionLaw(), 1.0, {}, lo, hi), std::invalid_argument);
  const auto corners = box_corners(Vector3d::Zero(), Vector3d::Ones());
  EXPECT_THROW(sweep_bounds(MotionLaw(), -1.0, corners, lo, hi), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Case-file reader

// Section readers take the file label and dimension from a NodeReader; the case reader sets the
// dimension from `dim`, this one directly.
class TestReader : public case_parse::NodeReader {
 public:
  explicit TestReader(int dim) : NodeReader("case.yaml") { dim_ = dim; }
};

MotionSpec parse_motion(const std::string& yaml, int dim = 2, const std::string& dir = "") {
  return case_parse::read_motion(TestReader(dim), YAML::Load(yaml)["motion"], "bodies[0].motion",
                                 dir);
}

// Succeeds when reading `yaml` throws a CaseError at case.yaml:`line` containing every part.
testing::AssertionResult ThrowsAt(const std::string& yaml, int line,
                                  const std::vector<std::string>& parts, int dim = 2) {
  try {
    parse_motion(yaml, dim, temp_dir().string());
  } catch (const CaseError& e) {
    const std::string what = e.what();
    if (e.line() != line || what.rfind("case.yaml:" + std::to_string(line) + ": ", 0) != 0) {
      return testing::AssertionFailure() << "expected line " << line << ", got: " << what;
    }
    for (const std::string& part : parts) {
      if (what.find(part) == std::string::npos) {
        return testing::AssertionFailure() << "'" << part << "' not in: " << what;
      }
    }
    return testing::AssertionSuccess();
  }
  return testing::AssertionFailure() << "no CaseError for: " << yaml;
}

TEST(ReadMotion, ParsesEveryType) {
  EXPECT_EQ(parse_motion("motion: none").type, Type::None);
  MotionSpec s = parse_motion(
      "motion: {type: linear, velocity: [0.1, 0], acceleration: [0, 0.5], stop: 2, ramp: 0.2}");
  EXPECT_EQ(s.type, Type::Linear);
  EXPECT_EQ(s.velocity, Vector3d(0.1, 0.0, 0.0));
  EXPECT_EQ(s.acceleration, Vector3d(0.0, 0.5, 0.0));
  EXPECT_EQ(s.start, 0.0);
  EXPECT_EQ(s.stop, 2.0);
  EXPECT_EQ(s.ramp, 0.2);
  s = parse_motion(
      "motion: {type: sinusoidal, amplitude: 0.05, period: 1.2, phase: 90, "
      "direction: [3, 4]}");
  EXPECT_EQ(s.amplitude, 0.05);  // metres: not converted
  EXPECT_EQ(s.period, 1.2);
  EXPECT_NEAR(s.phase, kPi / 2, 1e-15);  // degrees -> radians
  EXPECT_NEAR((s.direction - Vector3d(0.6, 0.8, 0.0)).norm(), 0.0, 1e-15);
  s = parse_motion("motion: {type: rotation, centre: [0.5, 0.1], rate: 30}");
  ASSERT_TRUE(s.rate.has_value());
  EXPECT_NEAR(*s.rate, 30 * kDeg, 1e-15);
  EXPECT_EQ(s.centre, Vector3d(0.5, 0.1, 0.0));
  EXPECT_EQ(s.axis, Vector3d::UnitZ());
  s = parse_motion(
      "motion: {type: rotation, centre: [0.5, 0.1], amplitude: 10, period: 2, "
      "phase: 0, axis: [0, 0, 1]}");
  EXPECT_FALSE(s.rate.has_value());
  EXPECT_NEAR(s.amplitude, 10 * kDeg, 1e-15);
  s = parse_motion("motion: {type: rotation, centre: [0, 0, 1], axis: [0, 2, 0], rate: -45}", 3);
  EXPECT_EQ(s.axis, Vector3d::UnitY());
  EXPECT_NEAR(*s.rate, -45 * kDeg, 1e-15);

  write_file("paddle.csv", "t,x\n0,0\n1,0.1\n2,0\n");  // relative to the case folder
  s = parse_motion(
      "motion: {type: file, file: paddle.csv, quantity: displacement, "
      "direction: [1, 0], start: 1}",
      2, temp_dir().string());
  EXPECT_EQ(s.file, (temp_dir() / "paddle.csv").string());
  EXPECT_EQ(s.series_value, (std::vector<double>{0.0, 0.1, 0.0}));
  EXPECT_EQ(s.quantity, MotionSpec::Quantity::Displacement);
  EXPECT_EQ(s.start, 1.0);
#ifdef SWELL_SOURCE_DIR
  s = parse_motion("motion: {type: file, file: motion_flap.csv, quantity: angle, centre: [2, 0]}",
                   2, std::string(SWELL_SOURCE_DIR) + "/tests/data");
  EXPECT_EQ(s.quantity, MotionSpec::Quantity::Angle);
  EXPECT_DOUBLE_EQ(s.series_value[2], 6.0 * kDeg);
  EXPECT_EQ(s.centre, Vector3d(2.0, 0.0, 0.0));
#endif
}

TEST(ReadMotion, ErrorsNameLineKeyAndFix) {
  const std::string m = "bodies[0].motion";
  EXPECT_TRUE(ThrowsAt("motion: 3", 1, {m + ": expected 'none' or a map such as {type:"}));
  EXPECT_TRUE(ThrowsAt("motion: {velocity: [1, 0]}", 1, {"missing required key '" + m + ".type'"}));
  EXPECT_TRUE(
      ThrowsAt("motion: {type: spin}", 1,
               {"unknown value 'spin'; expected one of: linear, sinusoidal, rotation, file"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: linear, speed: 1}", 1,
                       {"unknown key '" + m + ".speed'; allowed keys in " + m +
                        " for type linear: type, start, stop, ramp, velocity, acceleration"}));
  EXPECT_TRUE(
      ThrowsAt("motion: {type: sinusoidal, amplitude: 1, period: 1, rate: 3}", 1,
               {m + ".rate: sinusoidal motion takes no 'rate' (it belongs to type rotation)",
                "amplitude, period, phase, direction"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: linear}", 1, {"needs 'velocity' [m/s] and/or"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: linear, velocity: [1, 0, 0]}", 1,
                       {m + ".velocity: expected a list of 2 numbers"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: sinusoidal, amplitude: 1, period: 0}", 1,
                       {m + ".period: expected a number > 0"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: linear, velocity: [1, 0], ramp: -1}", 1,
                       {m + ".ramp: expected a number >= 0"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: linear, velocity: [1, 0], start: 2, stop: 1.5}", 1,
                       {m + ".stop: expected a number > start (2 s), got '1.5'"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: sinusoidal, amplitude: 1, period: 1, direction: [0, 0]}", 1,
                       {m + ".direction: expected a non-zero vector"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: rotation, centre: [0, 0], rate: 1, axis: [1, 0, 0]}", 1,
                       {m + ".axis: a 2D case rotates in the xy plane, about z"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: rotation, centre: [0, 0]}", 1,
                       {"needs either 'rate' (deg/s) or 'amplitude' (deg) and 'period' (s)"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: rotation, centre: [0, 0], rate: 1, amplitude: 2}", 1,
                       {m + ".rate: a rotation takes either 'rate'", "not both"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: rotation, rate: 1}", 1,
                       {"missing required key '" + m + ".centre'"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: rotation, centre: [0, 0], amplitude: 5}", 1,
                       {"missing required key '" + m + ".period'"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: file, file: x.csv}", 1,
                       {"missing required key '" + m + ".quantity'"}));
  EXPECT_TRUE(
      ThrowsAt("motion: {type: file, file: x.csv, quantity: angle, centre: [0, 0], "
               "direction: [1, 0]}",
               1, {m + ".direction: 'direction' is only used with quantity: displacement"}));
  // CSV problems are reported at the `file` key, with the CSV's own file and line.
  write_file("bad.csv", "t,x\n0,0\n0.1,abc\n");
  const std::string bad = (temp_dir() / "bad.csv").string();
  EXPECT_TRUE(
      ThrowsAt("# a paddle\nmotion:\n  type: file\n  quantity: displacement\n"
               "  file: bad.csv\n",
               5, {m + ".file: " + bad + ":3: expected 2 numbers (t, value), got '0.1,abc'"}));
  EXPECT_TRUE(ThrowsAt("motion: {type: file, file: none.csv, quantity: angle, centre: [0, 0]}", 1,
                       {m + ".file: " + (temp_dir() / "none.csv").string() + ": cannot open"}));
}

// The wave kinds are a table of readers (case/motion.cpp): every kind of the schema's
// `wave:` forms has one, and none is missing from the schema (the schema's keys of each kind,
// "wave:<kind>", are what the reader accepts).
TEST(WaveKinds, TheReaderReadsEveryKindOfTheSchema) {
  std::vector<std::string> schema;
  for (const auto k : case_schema::forms("bodies[].motion", "wave")) schema.emplace_back(k);
  std::vector<std::string> readers = case_parse::wave_kind_names();
  std::sort(schema.begin(), schema.end());
  std::sort(readers.begin(), readers.end());
  EXPECT_EQ(readers, schema);
  EXPECT_EQ(readers.size(), 4u);  // regular, solitary, irregular, focused
}

}  // namespace
}  // namespace swell
