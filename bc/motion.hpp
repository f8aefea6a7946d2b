// Prescribed rigid-body motion of boundary bodies: a piston or flap wave paddle, a swaying tank.
//
// A MotionSpec (plain data, read from a body's `motion:` key by case/motion.cpp) becomes a
// MotionLaw, a value type that gives the body's pose at any time t as a pure function of t, so a
// run continued from a checkpoint moves its bodies exactly as the uninterrupted run does. The
// pose is a translation d(t) and a rotation by theta(t) about the spec's axis through its centre;
// a boundary particle with reference (initial) position x_ref is at
//   x = centre + d + R(theta) (x_ref - centre),   v = dv + omega axis x (x - centre - d).
// Velocities are the exact time derivatives of the positions (analytic, not differenced).
//
// Rules common to every law (T = stop - start, local time tau = t - start):
// - tau is clamped to [0, T]. Before `start` the pose is the law at tau = 0 and the velocities
//   are zero; from `stop` on (t >= stop) the pose is frozen at tau = T and the velocities are
//   exactly zero. On [start, stop) the velocities are the law's.
// - Ramp: r(s) = s^2 (3 - 2 s), s = clamp(tau / ramp, 0, 1) (smoothstep; r = 1 when ramp = 0).
//   Constant-velocity laws (linear, rotation with a rate) ramp the VELOCITY, v = r(tau) (V + A
//   tau), and integrate it exactly, so the body starts from rest without a jump in position or
//   velocity. Oscillatory laws (sinusoidal translation or rotation) and File ramp the
//   DISPLACEMENT: d = r(tau) f(tau), dv = r'(tau) f(tau) + r(tau) f'(tau).
// - The body's particles are generated at the reference pose (d = 0, theta = 0). A law whose
//   value at tau = 0 is not zero (a phase without a ramp, a table not starting at 0) moves them
//   there at the first placement.
//
// Units inside MotionSpec are SI throughout: metres, seconds, radians (the case file takes
// degrees for angles, phases and rates; case/motion.cpp converts).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "waves/wavemaker.hpp"

namespace swell {

struct MotionSpec {
  enum class Type { None, Linear, Sinusoidal, Rotation, File, Wave };
  Type type = Type::None;

  // Linear translation: velocity [m/s] and constant acceleration [m/s^2].
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();

  // Sinusoidal translation: d(tau) = amplitude sin(2 pi tau / period + phase) direction.
  // Sinusoidal rotation (Rotation without a rate): theta(tau) = amplitude sin(...) likewise.
  double amplitude = 0.0;  // [m] for a translation, [rad] for a rotation
  double period = 0.0;     // [s]
  double phase = 0.0;      // [rad]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit vector

  // Rotation (and File with quantity Angle) about the axis through `centre`; 2D: axis z.
  // A constant rate [rad/s] if set, else the sinusoidal angle above.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit vector
  std::optional<double> rate{};

  // File: a time series (tau, value) interpolated by a C1 cubic Hermite spline; value is a
  // displacement [m] along `direction` or an angle [rad] about axis/centre.
  enum class Quantity { Displacement, Angle };
  Quantity quantity = Quantity::Displacement;
  std::string file{};                  // where the series came from, for messages
  std::vector<double> series_t{};      // local time tau [s], strictly increasing, >= 2 entries
  std::vector<double> series_value{};  // SI: m or rad

  // Wave: a wavemaker paddle driven by a signal X(tau) (waves/wavemaker.hpp), the displacement
  // of the paddle's still-water-level point along `direction`. A piston translates by X; a flap
  // turns about `axis` through `centre` (its hinge) by theta = atan(X / lever), lever = the
  // height of the still-water level above the hinge, so its SWL point moves by exactly X
  // horizontally (the axis is set to up x direction, so a positive theta moves it along
  // `direction`). Ramped like File. `wave_label` describes the wave for the run header.
  std::shared_ptr<const waves::PaddleSignal> paddle{};
  double lever = 0.0;  // [m], flap
  std::string wave_label{};
  std::vector<std::string> wave_notes{};  // validity warnings (waves/theory.hpp)
  // The wave as the case file gave it (for `swell foam`, which maps it to interFoam's
  // waveModels): kind ("regular", "solitary", "irregular", "focused"), H [m], T [s] (regular),
  // order (regular), phase [rad] (regular).
  std::string wave_kind{};
  double wave_height = 0.0, wave_period = 0.0, wave_phase = 0.0;
  int wave_order = 1;

  // Wave, piston only: active absorption (bc/absorption.hpp), read from `absorption:`.
  struct Absorption {
    enum class Gain { Tuned, Shallow };
    Gain gain = Gain::Tuned;
    std::optional<double> distance{};  // paddle face to the measuring line [m]; default support
    std::optional<double> filter{};    // low-pass time constant [s]; default 0.02 T_ref
    std::optional<double> drift{};     // drift time constant [s]; default 10 T_ref
  };
  std::optional<Absorption> absorption{};
  double bed = 0.0;  // Wave: bed elevation at the paddle [m] (still-water level = bed + depth)
  double g = 9.81;   // Wave: |gravity| [m/s^2]

  double start = 0.0;                                     // [s]
  double stop = std::numeric_limits<double>::infinity();  // [s], > start
  double ramp = 0.0;                                      // [s], >= 0
};

// Pose of a moving body: translation d and its velocity dv; rotation angle theta and its rate
// omega about the law's axis through its centre.
struct RigidPose {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  Eigen::Vector3d dv = Eigen::Vector3d::Zero();
  double theta = 0.0;
  double omega = 0.0;
};

// A pose as a matrix and vectors, computed once per body and step and applied to each of its
// particles (no trigonometry per particle): x = origin + R (x_ref - centre),
// v = dv + spin x (R (x_ref - centre)).
struct RigidPlacement {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d dv = Eigen::Vector3d::Zero(), spin = Eigen::Vector3d::Zero();
  void apply(const Eigen::Vector3d& x_ref, Eigen::Vector3d& x, Eigen::Vector3d& v) const {
    const Eigen::Vector3d r = rotation * (x_ref - centre);
    x = origin + r;
    v = dv + spin.cross(r);
  }
};

// A time series read by load_motion_csv(): t [s] and value in SI (m, or rad for an angle).
struct MotionSeries {
  std::vector<double> t, value;
};

// Reads a motion time series from a CSV file: lines starting with '#' and blank lines are
// skipped; the first other line is a header (e.g. "t,x") unless it already holds two numbers;
// every further line holds two comma-separated numbers t, value, with t strictly increasing and
// at least 2 rows. An Angle is given in degrees in the file and returned in radians. Throws
// std::invalid_argument("<path>:<line>: <what was expected>") on any problem.
// With a `column` name, the header is required and names the columns: t is the first column and
// the value the named one, so a measured record with more columns (probes, velocities) is read
// as it is; rows need at least as many comma-separated numbers as the value's column number.
MotionSeries load_motion_csv(const std::string& path, MotionSpec::Quantity quantity,
                             const std::string& column = "");

class MotionLaw {
 public:
  MotionLaw() = default;  // no motion
  // Checks the spec (period > 0, ramp >= 0, stop > start, non-zero direction and axis, a valid
  // series) and throws std::invalid_argument naming the problem; normalises direction and axis.
  explicit MotionLaw(const MotionSpec& spec);

  bool moves() const { return spec_.type != MotionSpec::Type::None; }
  // Whether the pose can include a rotation (rotation laws, angle records, a flap paddle).
  bool rotates() const;
  const MotionSpec& spec() const { return spec_; }

  // The pose at time t (rules in the file comment). No allocation.
  RigidPose pose(double t) const;

  // Moves a point with reference position x_ref to its place and velocity in `pose`. In 2D, pass
  // 3-vectors with z = 0 and an axis along z: x and v then have z = 0 exactly.
  void place(const RigidPose& pose, const Eigen::Vector3d& x_ref, Eigen::Vector3d& x,
             Eigen::Vector3d& v) const;
  // The same as a matrix and vectors, to apply to many points (RigidPlacement::apply).
  RigidPlacement placement(const RigidPose& pose) const;

  // Time scale of repeated motion, for sampling (sweep_bounds): the period of a sinusoid, the
  // time of one turn at the full rate; 0 when the law has none.
  double cycle_time() const;

 private:
  void law_at(double tau, RigidPose& pose) const;  // the law at local time tau, with velocities
  void table_at(double tau, double& value, double& rate) const;  // Hermite interpolant

  MotionSpec spec_;
  double angular_frequency_ = 0.0;  // 2 pi / period
  std::vector<double> slopes_;      // File: d value / d tau at each knot
};

// The 8 corners of the box [lo, hi] (4 distinct ones when lo.z = hi.z = 0, as in 2D). A rigid
// motion maps a box into the convex hull of its moved corners, so their sweep bounds the box's.
std::array<Eigen::Vector3d, 8> box_corners(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

// Bounding box [lo, hi] of `points` (reference positions) over their motion in [0, t_end], for
// sizing the simulation domain so a moving body is never excluded. The points themselves are
// included (the particles are created there), then the law is sampled at 256 uniform times, or
// 64 per cycle_time() if that is more (at most 2^20), plus start, stop and, for File, every table
// time. The box is then padded by the longest step any point makes between two consecutive
// samples: a point's path between two samples stays within half its length of one of them, so
// the pad covers whatever sampling misses while no such path is longer than twice the longest
// step, which holds for turns of up to 200 degrees between samples and for sinusoids sampled
// 64 times per period. Axes on which every point stays at 0 (z in 2D) are not padded. Cost:
// samples x points placements, so pass the corners of the body's bounding box (box_corners)
// rather than every particle. Throws std::invalid_argument if t_end < 0 or `points` is empty.
void sweep_bounds(const MotionLaw& law, double t_end, std::span<const Eigen::Vector3d> points,
                  Eigen::Vector3d& lo, Eigen::Vector3d& hi);

}  // namespace swell
