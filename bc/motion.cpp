// Prescribed rigid-body motion laws (bc/motion.hpp).
#include "bc/motion.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace swell {

namespace {

std::string format_number(double v) {
  std::ostringstream out;
  out.precision(10);
  out << v;
  return out.str();
}

// Smoothstep ramp r(s) = s^2 (3 - 2 s), s = tau / ramp, and its time derivative.
struct Ramp {
  double r = 1.0, dr = 0.0;
};

Ramp ramp_at(double tau, double ramp) {
  if (ramp <= 0.0 || tau >= ramp) return {};
  const double s = std::max(tau, 0.0) / ramp;
  return {s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s) / ramp};
}

// Integrals of the ramp from 0 to tau: i0 = int r(u) du, i1 = int r(u) u du. With u = R s,
// int_0^s (3 s^2 - 2 s^3) = s^3 - s^4 / 2 and int_0^s (3 s^3 - 2 s^4) = 3 s^4 / 4 - 2 s^5 / 5;
// past the ramp r = 1, so i0 = R / 2 + (tau - R) and i1 = 7 R^2 / 20 + (tau^2 - R^2) / 2.
void ramp_integrals(double tau, double ramp, double& i0, double& i1) {
  if (ramp <= 0.0) {
    i0 = tau;
    i1 = 0.5 * tau * tau;
  } else if (tau < ramp) {
    const double s = tau / ramp, s3 = s * s * s, s4 = s3 * s;
    i0 = ramp * (s3 - 0.5 * s4);
    i1 = ramp * ramp * (0.75 * s4 - 0.4 * s4 * s);
  } else {
    i0 = 0.5 * ramp + (tau - ramp);
    i1 = 0.35 * ramp * ramp + 0.5 * (tau - ramp) * (tau + ramp);
  }
}

void check_unit(Eigen::Vector3d& v, const char* name) {
  const double n = v.norm();
  if (!(n > 0.0) || !std::isfinite(n)) {
    throw std::invalid_argument(std::string("motion: the ") + name +
                                " must be a non-zero finite vector");
  }
  v /= n;
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// A whole field as a finite number (locale-independent); a leading '+' is accepted.
bool parse_number(std::string_view field, double& value) {
  field = trim(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return false;
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

// Splits "t, value" into two numbers; false if the line is not exactly that.
bool parse_row(std::string_view line, double& t, double& value) {
  const auto comma = line.find(',');
  if (comma == std::string_view::npos) return false;
  return parse_number(line.substr(0, comma), t) && parse_number(line.substr(comma + 1), value);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// CSV time series

namespace {

// The comma-separated fields of a line, trimmed.
std::vector<std::string_view> fields_of(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const auto comma = line.find(',', start);
    out.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

// load_motion_csv with a named value column (t is the first column).
MotionSeries load_motion_column(const std::string& path, MotionSpec::Quantity quantity,
                                const std::string& column) {
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument(path + ": cannot open the motion time series for reading");
  }
  const double scale = quantity == MotionSpec::Quantity::Angle ? std::numbers::pi / 180.0 : 1.0;
  MotionSeries series;
  std::string raw;
  int line_no = 0;
  std::size_t index = 0;
  bool header_seen = false;
  while (std::getline(in, raw)) {
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == '#') continue;
    const std::vector<std::string_view> fields = fields_of(line);
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (!header_seen) {
      header_seen = true;
      const auto it = std::find(fields.begin(), fields.end(), std::string_view(column));
      if (it == fields.begin() || it == fields.end()) {
        std::string names;
        for (std::size_t i = 1; i < fields.size(); ++i)
          names += (i > 1 ? ", " : "") + std::string(fields[i]);
        throw std::invalid_argument(where + "no value column '" + column +
                                    "' in the header (the first column is the time; the others "
                                    "are: " +
                                    names + ")");
      }
      index = static_cast<std::size_t>(it - fields.begin());
      continue;
    }
    double t = 0.0, value = 0.0;
    if (fields.size() <= index || !parse_number(fields[0], t) ||
        !parse_number(fields[index], value)) {
      throw std::invalid_argument(where + "expected numbers in column 1 (t) and column " +
                                  std::to_string(index + 1) + " (" + column + ")");
    }
    if (!series.t.empty() && !(t > series.t.back())) {
      throw std::invalid_argument(where +
                                  "times must increase strictly, but t = " + format_number(t) +
                                  " follows t = " + format_number(series.t.back()));
    }
    series.t.push_back(t);
    series.value.push_back(value * scale);
  }
  if (in.bad()) throw std::invalid_argument(path + ": error while reading the file");
  if (series.t.size() < 2) {
    throw std::invalid_argument(path + ": expected at least 2 data rows after the header, found " +
                                std::to_string(series.t.size()));
  }
  return series;
}
}  // namespace

MotionSeries load_motion_csv(const std::string& path, MotionSpec::Quantity quantity,
                             const std::string& column) {
  if (!column.empty()) return load_motion_column(path, quantity, column);
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument(path + ": cannot open the motion time series for reading");
  }
  const double scale =
      quantity == MotionSpec::Quantity::Angle ? std::numbers::pi / 180.0 : 1.0;  // deg -> rad
  MotionSeries series;
  std::string raw;
  int line_no = 0, last_line = 0;
  bool header_seen = false;
  while (std::getline(in, raw)) {
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == '#') continue;
    double t = 0.0, value = 0.0;
    const bool row = parse_row(line, t, value);
    if (!header_seen) {
      header_seen = true;
      if (!row) continue;  // the header line
    }
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (!row) {
      std::string shown(line.substr(0, 60));
      if (line.size() > 60) shown += "...";
      throw std::invalid_argument(where + "expected 2 numbers (t, value), got '" + shown + "'");
    }
    if (!series.t.empty() && !(t > series.t.back())) {
      throw std::invalid_argument(where +
                                  "times must increase strictly, but t = " + format_number(t) +
                                  " follows t = " + format_number(series.t.back()) + " (line " +
                                  std::to_string(last_line) + ")");
    }
    series.t.push_back(t);
    series.value.push_back(value * scale);
    last_line = line_no;
  }
  if (in.bad()) throw std::invalid_argument(path + ": error while reading the file");
  if (series.t.size() < 2) {
    throw std::invalid_argument(path + ": expected at least 2 data rows (t, value) after the " +
                                "header, found " + std::to_string(series.t.size()));
  }
  return series;
}

// ---------------------------------------------------------------------------------------------
// MotionLaw

MotionLaw::MotionLaw(const MotionSpec& spec) : spec_(spec) {
  using Type = MotionSpec::Type;
  if (!(spec_.stop > spec_.start)) {
    throw std::invalid_argument("motion: stop (" + format_number(spec_.stop) +
                                " s) must be greater than start (" + format_number(spec_.start) +
                                " s)");
  }
  if (!(spec_.ramp >= 0.0)) {
    throw std::invalid_argument("motion: ramp must be >= 0 s, got " + format_number(spec_.ramp));
  }
  const bool flap = spec_.type == Type::Wave && spec_.paddle &&
                    spec_.paddle->paddle.type == waves::PaddleGeometry::Type::Flap;
  const bool oscillates =
      spec_.type == Type::Sinusoidal || (spec_.type == Type::Rotation && !spec_.rate);
  if (spec_.type == Type::Sinusoidal || spec_.type == Type::Wave ||
      (spec_.type == Type::File && spec_.quantity == MotionSpec::Quantity::Displacement)) {
    check_unit(spec_.direction, "direction");
  }
  if (spec_.type == Type::Wave) {
    if (!spec_.paddle) throw std::invalid_argument("motion: a wave paddle needs its signal");
    if (flap && !(spec_.lever > 0.0)) {
      throw std::invalid_argument("motion: a flap needs its hinge below the still-water level");
    }
  }
  if (rotates()) check_unit(spec_.axis, "rotation axis");
  if (oscillates) {
    if (!(spec_.period > 0.0) || !std::isfinite(spec_.period)) {
      throw std::invalid_argument("motion: period must be a number > 0 s, got " +
                                  format_number(spec_.period));
    }
    angular_frequency_ = 2.0 * std::numbers::pi / spec_.period;
  }
  if (spec_.type == Type::File) {
    const std::vector<double>& t = spec_.series_t;
    const std::vector<double>& y = spec_.series_value;
    const std::string name = spec_.file.empty() ? "the motion series" : spec_.file;
    if (t.size() < 2 || t.size() != y.size()) {
      throw std::invalid_argument(name + ": expected at least 2 (t, value) rows, got " +
                                  std::to_string(t.size()) + " times and " +
                                  std::to_string(y.size()) + " values");
    }
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (!(t[i] > t[i - 1])) throw std::invalid_argument(name + ": times must increase strictly");
    }
    // Knot slopes: the derivative of the parabola through three neighbouring points, second
    // order on a non-uniform grid ("Bessel interpolation", de Boor, A Practical Guide to Splines,
    // 2001, ch. IV); at the ends the same parabola differentiated one-sidedly, so quadratics are
    // reproduced exactly. Two points give the straight line.
    const std::size_t n = t.size();
    slopes_.assign(n, (y[1] - y[0]) / (t[1] - t[0]));
    if (n >= 3) {
      // Newton form of the parabola through knots i-1, i, i+1:
      //   p(t) = y[i-1] + s0 (t - t[i-1]) + c (t - t[i-1]) (t - t[i]),  c = (s1 - s0) / (h0 + h1),
      // differentiated at knot `at`; at t[i] this is (h1 s0 + h0 s1) / (h0 + h1).
      const auto parabola_slope = [&](std::size_t i, std::size_t at) {
        const double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
        const double s0 = (y[i] - y[i - 1]) / h0, s1 = (y[i + 1] - y[i]) / h1;
        const double c = (s1 - s0) / (h0 + h1);
        return s0 + c * (2.0 * t[at] - t[i - 1] - t[i]);
      };
      slopes_[0] = parabola_slope(1, 0);
      for (std::size_t i = 1; i + 1 < n; ++i) slopes_[i] = parabola_slope(i, i);
      slopes_[n - 1] = parabola_slope(n - 2, n - 1);
    }
  }
}

double MotionLaw::cycle_time() const {
  switch (spec_.type) {
    case MotionSpec::Type::Sinusoidal:
      return spec_.period;
    case MotionSpec::Type::Wave:
      return spec_.paddle->shortest_period();
    case MotionSpec::Type::Rotation:
      if (!spec_.rate) return spec_.period;
      return *spec_.rate != 0.0 ? 2.0 * std::numbers::pi / std::abs(*spec_.rate) : 0.0;
    default:
      return 0.0;
  }
}

void MotionLaw::table_at(double tau, double& value, double& rate) const {
  const std::vector<double>& t = spec_.series_t;
  const std::vector<double>& y = spec_.series_value;
  if (tau < t.front() || tau >= t.back()) {  // outside the table: hold the end value
    value = tau < t.front() ? y.front() : y.back();
    rate = 0.0;
    return;
  }
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), tau) - t.begin()) - 1;
  const double h = t[i + 1] - t[i], s = (tau - t[i]) / h, s2 = s * s, s3 = s2 * s;
  const double m0 = slopes_[i] * h, m1 = slopes_[i + 1] * h;
  // Cubic Hermite basis h00, h10, h01, h11 and their derivatives in s.
  value = (2 * s3 - 3 * s2 + 1) * y[i] + (s3 - 2 * s2 + s) * m0 + (3 * s2 - 2 * s3) * y[i + 1] +
          (s3 - s2) * m1;
  rate =
      ((6 * s2 - 6 * s) * (y[i] - y[i + 1]) + (3 * s2 - 4 * s + 1) * m0 + (3 * s2 - 2 * s) * m1) /
      h;
}

void MotionLaw::law_at(double tau, RigidPose& p) const {
  const Ramp ramp = ramp_at(tau, spec_.ramp);
  switch (spec_.type) {
    case MotionSpec::Type::None:
      break;
    case MotionSpec::Type::Linear: {
      double i0 = 0.0, i1 = 0.0;
      ramp_integrals(tau, spec_.ramp, i0, i1);
      p.d = spec_.velocity * i0 + spec_.acceleration * i1;
      p.dv = ramp.r * (spec_.velocity + spec_.acceleration * tau);
      break;
    }
    case MotionSpec::Type::Sinusoidal: {
      const double arg = angular_frequency_ * tau + spec_.phase;
      const double f = spec_.amplitude * std::sin(arg);
      const double df = spec_.amplitude * angular_frequency_ * std::cos(arg);
      p.d = (ramp.r * f) * spec_.direction;
      p.dv = (ramp.dr * f + ramp.r * df) * spec_.direction;
      break;
    }
    case MotionSpec::Type::Rotation:
      if (spec_.rate) {
        double i0 = 0.0, i1 = 0.0;
        ramp_integrals(tau, spec_.ramp, i0, i1);
        p.theta = *spec_.rate * i0;
        p.omega = ramp.r * *spec_.rate;
      } else {
        const double arg = angular_frequency_ * tau + spec_.phase;
        const double f = spec_.amplitude * std::sin(arg);
        const double df = spec_.amplitude * angular_frequency_ * std::cos(arg);
        p.theta = ramp.r * f;
        p.omega = ramp.dr * f + ramp.r * df;
      }
      break;
    case MotionSpec::Type::File: {
      double f = 0.0, df = 0.0;
      table_at(tau, f, df);
      const double value = ramp.r * f, rate = ramp.dr * f + ramp.r * df;
      if (spec_.quantity == MotionSpec::Quantity::Angle) {
        p.theta = value;
        p.omega = rate;
      } else {
        p.d = value * spec_.direction;
        p.dv = rate * spec_.direction;
      }
      break;
    }
    case MotionSpec::Type::Wave: {
      const double f = spec_.paddle->displacement(tau), df = spec_.paddle->velocity(tau);
      const double x = ramp.r * f, rate = ramp.dr * f + ramp.r * df;
      if (spec_.paddle->paddle.type == waves::PaddleGeometry::Type::Flap) {
        // theta = atan(X / l): d theta / dt = l X' / (l^2 + X^2).
        const double l = spec_.lever;
        p.theta = std::atan2(x, l);
        p.omega = l * rate / (l * l + x * x);
      } else {
        p.d = x * spec_.direction;
        p.dv = rate * spec_.direction;
      }
      break;
    }
  }
}

bool MotionLaw::rotates() const {
  using Type = MotionSpec::Type;
  const bool flap = spec_.type == Type::Wave && spec_.paddle &&
                    spec_.paddle->paddle.type == waves::PaddleGeometry::Type::Flap;
  return spec_.type == Type::Rotation || flap ||
         (spec_.type == Type::File && spec_.quantity == MotionSpec::Quantity::Angle);
}

RigidPose MotionLaw::pose(double t) const {
  RigidPose p;
  if (!moves()) return p;
  const double span = spec_.stop - spec_.start;
  const double tau = std::clamp(t - spec_.start, 0.0, span);
  law_at(tau, p);
  if (t < spec_.start || t >= spec_.stop) {  // at rest before start, frozen from stop on
    p.dv.setZero();
    p.omega = 0.0;
  }
  return p;
}

RigidPlacement MotionLaw::placement(const RigidPose& pose) const {
  // With the axis exactly along z the matrix has zero z row and column off the diagonal, so
  // points and velocities with z = 0 keep z = 0 exactly.
  RigidPlacement p;
  p.rotation = Eigen::AngleAxisd(pose.theta, spec_.axis).toRotationMatrix();
  p.centre = spec_.centre;
  p.origin = spec_.centre + pose.d;
  p.dv = pose.dv;
  p.spin = pose.omega * spec_.axis;
  return p;
}

void MotionLaw::place(const RigidPose& pose, const Eigen::Vector3d& x_ref, Eigen::Vector3d& x,
                      Eigen::Vector3d& v) const {
  placement(pose).apply(x_ref, x, v);
}

// ---------------------------------------------------------------------------------------------
// Swept bounds

std::array<Eigen::Vector3d, 8> box_corners(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::array<Eigen::Vector3d, 8> corners;
  for (int c = 0; c < 8; ++c) {
    corners[static_cast<std::size_t>(c)] = Eigen::Vector3d(
        (c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
  }
  return corners;
}

void sweep_bounds(const MotionLaw& law, double t_end, std::span<const Eigen::Vector3d> points,
                  Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  if (!(t_end >= 0.0) || !std::isfinite(t_end)) {
    throw std::invalid_argument("sweep_bounds: the end time must be a finite number >= 0, got " +
                                format_number(t_end));
  }
  if (points.empty()) throw std::invalid_argument("sweep_bounds: no points to sweep");
  lo = points[0];
  hi = points[0];
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (!law.moves()) return;

  constexpr std::size_t kMaxSamples = std::size_t(1) << 20;
  std::size_t uniform = 256;
  if (const double cycle = law.cycle_time(); cycle > 0.0) {
    const double per_cycle = std::ceil(64.0 * t_end / cycle);
    uniform = static_cast<std::size_t>(std::clamp(per_cycle, 256.0, double(kMaxSamples)));
  }
  std::vector<double> times;
  for (std::size_t k = 0; k <= uniform; ++k) times.push_back(t_end * double(k) / double(uniform));
  const MotionSpec& spec = law.spec();
  const auto add = [&](double t) {
    if (t >= 0.0 && t <= t_end) times.push_back(t);
  };
  add(spec.start);
  add(spec.stop);
  if (spec.type == MotionSpec::Type::File) {
    for (std::size_t i = 0; i < spec.series_t.size() && times.size() < 2 * kMaxSamples; ++i) {
      add(spec.start + spec.series_t[i]);
    }
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());

  std::vector<Eigen::Vector3d> previous(points.size());
  double pad = 0.0;
  Eigen::Vector3d x, v;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const RigidPose pose = law.pose(times[k]);
    for (std::size_t i = 0; i < points.size(); ++i) {
      law.place(pose, points[i], x, v);
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
      if (k > 0) pad = std::max(pad, (x - previous[i]).norm());
      previous[i] = x;
    }
  }
  // Axes on which every point stays at 0 (z in 2D) are not padded, so 2D boxes keep z = 0.
  for (int a = 0; a < 3; ++a) {
    if (lo[a] == 0.0 && hi[a] == 0.0) continue;
    lo[a] -= pad;
    hi[a] += pad;
  }
}

}  // namespace swell
