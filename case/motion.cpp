// Parsing of a body's `motion:` key into MotionSpec (bc/motion.hpp).
//
//   motion: none
//   motion: {type: linear, velocity: [..], acceleration: [..]}            m/s, m/s^2
//   motion: {type: sinusoidal, amplitude: A, period: P, phase: deg, direction: [..]}
//   motion: {type: rotation, centre: [..], rate: deg/s, axis: [x, y, z]}
//   motion: {type: rotation, centre: [..], amplitude: deg, period: P, phase: deg, axis: [..]}
//   motion: {type: file, file: f.csv, quantity: displacement, direction: [..]}
//   motion: {type: file, file: f.csv, quantity: angle, centre: [..], axis: [..]}
//   motion: {type: wave, paddle: piston|flap, wave: regular|solitary|focused|irregular,
//            depth: d, direction: [..], ...}          the wave's keys: read_wave below
// Every type also takes start, stop and ramp (seconds). Angles, phases and rates are in degrees
// in the file and radians in MotionSpec. The axis is always 3 numbers; in 2D it must be z. As in
// the gauge reader, a key that belongs to another type is reported as such.
#include "case/motion.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "case/schema.hpp"
#include "waves/spectrum.hpp"
#include "waves/theory.hpp"

namespace swell::case_parse {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

struct MotionTypeInfo {
  std::string_view name;
  MotionSpec::Type type;
  Names keys;  // besides the common keys
};

constexpr std::string_view kSection = "bodies[].motion";  // the schema's (case/schema.cpp)

// The types in the schema's order, each with its keys from the schema.
const std::vector<MotionTypeInfo>& motion_types() {
  static const std::vector<MotionTypeInfo> types = [] {
    const std::pair<std::string_view, MotionSpec::Type> known[] = {
        {"linear", MotionSpec::Type::Linear},
        {"sinusoidal", MotionSpec::Type::Sinusoidal},
        {"rotation", MotionSpec::Type::Rotation},
        {"file", MotionSpec::Type::File},
        {"wave", MotionSpec::Type::Wave}};
    std::vector<MotionTypeInfo> out;
    for (const std::string_view name : case_schema::forms(kSection)) {
      const auto it = std::find_if(std::begin(known), std::end(known),
                                   [&](const auto& k) { return k.first == name; });
      if (it == std::end(known))
        throw std::logic_error("motion type '" + std::string(name) + "' has no reader");
      out.push_back({name, it->second, case_schema::form_keys(kSection, name)});
    }
    return out;
  }();
  return types;
}

const char* const kExample = "a map such as {type: sinusoidal, amplitude: 0.05, period: 1.2}";

class MotionReader : private NodeReader {
 public:
  MotionReader(const NodeReader& base, std::string case_dir, double g, double dp)
      : NodeReader(base), case_dir_(std::move(case_dir)), g_(g), dp_(dp) {}

  MotionSpec read(const YAML::Node& node, const std::string& path) const;

  // The wave kinds' readers (the table wave_kinds()): each reads its own keys (the schema's
  // form "wave:<kind>"), makes the paddle's signal, adds to the run header's label and returns
  // the period the default ramp (two of them) is taken from, 0 for none.
  struct WaveRead;
  double read_regular(WaveRead& w) const;
  double read_solitary(WaveRead& w) const;
  double read_irregular(WaveRead& w) const;
  double read_focused(WaveRead& w) const;

 private:
  const MotionTypeInfo& read_type(const YAML::Node& node, const std::string& path) const;
  void check_motion_keys(const YAML::Node& node, const std::string& path,
                         const MotionTypeInfo& type) const;
  void read_times(const YAML::Node& node, const std::string& path, MotionSpec& spec) const;
  void read_linear(const YAML::Node& node, const std::string& path, MotionSpec& spec) const;
  void read_sinusoid(const YAML::Node& node, const std::string& path, MotionSpec& spec,
                     double amplitude_unit) const;
  void read_rotation(const YAML::Node& node, const std::string& path, MotionSpec& spec) const;
  void read_file(const YAML::Node& node, const std::string& path, MotionSpec& spec) const;
  void read_absorption(const YAML::Node& node, const std::string& path, const std::string& kind,
                       MotionSpec& spec) const;
  void read_wave(const YAML::Node& node, const std::string& path, MotionSpec& spec) const;
  waves::SpectrumSpec read_spectrum(WaveRead& w) const;
  void component_paddle(WaveRead& w, const std::vector<waves::SurfaceComponent>& surface) const;
  void second_order_note(WaveRead& w, int n) const;
  void read_pivot(const YAML::Node& node, const std::string& path, MotionSpec& spec) const;
  void read_direction(const YAML::Node& node, const std::string& path, MotionSpec& spec) const;
  Eigen::Vector3d unit(const YAML::Node& node, const std::string& path, int count) const;
  double positive_number(const YAML::Node& node, const std::string& path, const char* key) const {
    return number_if(
        require(node, path, key), child(path, key), [](double v) { return v > 0.0; },
        "a number > 0");
  }

  std::string case_dir_;
  double g_ = 9.81;
  double dp_ = 0.0;
};

// What a wave kind's reader reads from and writes to: the wave's node, the paddle, the order,
// the run header's label, the motion spec; the paddle signal it makes.
struct MotionReader::WaveRead {
  const YAML::Node& node;
  const std::string& path;
  const std::string& kind;
  const waves::PaddleGeometry& paddle;
  bool flap = false;
  int order = 1;
  std::ostringstream& label;
  MotionSpec& spec;
  waves::PaddleSignal signal;
};

// The wave kinds (`wave:` of a `type: wave` motion), each with its reader. A kind's keys are
// the schema's form "wave:<kind>" (case/schema.cpp); a kind in the schema without a reader here
// is a programming error (WaveKinds.TheReaderReadsEveryKindOfTheSchema).
struct WaveKind {
  std::string_view name;
  double (MotionReader::*read)(MotionReader::WaveRead&) const;
};
const std::vector<WaveKind>& wave_kinds() {
  static const std::vector<WaveKind> kinds{{"regular", &MotionReader::read_regular},
                                           {"solitary", &MotionReader::read_solitary},
                                           {"irregular", &MotionReader::read_irregular},
                                           {"focused", &MotionReader::read_focused}};
  return kinds;
}

MotionSpec MotionReader::read(const YAML::Node& node, const std::string& path) const {
  if (node.IsScalar() && node.Scalar() == "none") return MotionSpec{};
  expect(node.IsMap(), node, path, std::string("'none' or ") + kExample);
  MotionSpec spec;
  const MotionTypeInfo& type = read_type(node, path);
  spec.type = type.type;
  check_motion_keys(node, path, type);
  read_times(node, path, spec);
  switch (spec.type) {
    case MotionSpec::Type::None:
      break;
    case MotionSpec::Type::Linear:
      read_linear(node, path, spec);
      break;
    case MotionSpec::Type::Sinusoidal:
      read_sinusoid(node, path, spec, 1.0);
      read_direction(node, path, spec);
      break;
    case MotionSpec::Type::Rotation:
      read_rotation(node, path, spec);
      break;
    case MotionSpec::Type::File:
      read_file(node, path, spec);
      break;
    case MotionSpec::Type::Wave:
      read_wave(node, path, spec);
      break;
  }
  try {
    MotionLaw check(spec);  // a backstop: the checks above should leave nothing to find
  } catch (const std::invalid_argument& e) {
    fail(node, path + ": " + e.what());
  }
  return spec;
}

const MotionTypeInfo& MotionReader::read_type(const YAML::Node& node,
                                              const std::string& path) const {
  Names names;
  for (const MotionTypeInfo& info : motion_types()) names.push_back(info.name);
  const std::string type = choice(require(node, path, "type"), child(path, "type"), names);
  const auto& types = motion_types();
  return *std::find_if(types.begin(), types.end(),
                       [&](const MotionTypeInfo& info) { return info.name == type; });
}

void MotionReader::check_motion_keys(const YAML::Node& node, const std::string& path,
                                     const MotionTypeInfo& type) const {
  Names allowed = case_schema::common_keys(kSection);
  allowed.insert(allowed.end(), type.keys.begin(), type.keys.end());
  const std::string context = " for type " + std::string(type.name);
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) continue;  // reported by check_keys below
    const std::string& key = entry.first.Scalar();
    if (contains(allowed, key)) continue;
    Names owners;
    for (const MotionTypeInfo& other : motion_types()) {
      if (contains(other.keys, key)) owners.push_back(other.name);
    }
    if (owners.empty()) continue;  // an unknown key, reported by check_keys below
    fail(entry.first, child(path, key) + ": " + std::string(type.name) + " motion takes no '" +
                          key + "' (it belongs to type" + (owners.size() > 1 ? "s " : " ") +
                          join(owners) + "); allowed keys in " + path + context + ": " +
                          join(allowed));
  }
  check_keys(node, path, allowed, context);
}

void MotionReader::read_times(const YAML::Node& node, const std::string& path,
                              MotionSpec& spec) const {
  if (auto v = find(node, "start")) {
    spec.start = number_if(
        *v, child(path, "start"), [](double s) { return s >= 0.0; },
        "a number >= 0 (seconds from the start of the run)");
  }
  if (auto v = find(node, "stop")) {
    const double start = spec.start;
    const auto start_node = find(node, "start");
    spec.stop = number_if(
        *v, child(path, "stop"), [start](double s) { return s > start; },
        "a number > start (" + (start_node ? start_node->Scalar() : std::string("0")) + " s)");
  }
  if (auto v = find(node, "ramp")) {
    spec.ramp = number_if(
        *v, child(path, "ramp"), [](double r) { return r >= 0.0; },
        "a number >= 0 (seconds; 0: no ramp)");
  }
}

void MotionReader::read_linear(const YAML::Node& node, const std::string& path,
                               MotionSpec& spec) const {
  const auto velocity = find(node, "velocity");
  const auto acceleration = find(node, "acceleration");
  if (!velocity && !acceleration) {
    fail(node, path +
                   ": linear motion needs 'velocity' [m/s] and/or 'acceleration' [m/s^2], "
                   "e.g. {type: linear, velocity: [0.1, 0]}");
  }
  if (velocity) spec.velocity = vector(*velocity, child(path, "velocity"));
  if (acceleration) spec.acceleration = vector(*acceleration, child(path, "acceleration"));
}

// amplitude, period, phase; the amplitude is multiplied by `amplitude_unit` (degrees to radians
// for a rotation).
void MotionReader::read_sinusoid(const YAML::Node& node, const std::string& path, MotionSpec& spec,
                                 double amplitude_unit) const {
  spec.amplitude =
      amplitude_unit * number(require(node, path, "amplitude"), child(path, "amplitude"));
  spec.period = number_if(
      require(node, path, "period"), child(path, "period"), [](double p) { return p > 0.0; },
      "a number > 0 (seconds)");
  if (auto v = find(node, "phase")) spec.phase = kDegree * number(*v, child(path, "phase"));
}

void MotionReader::read_rotation(const YAML::Node& node, const std::string& path,
                                 MotionSpec& spec) const {
  read_pivot(node, path, spec);
  const auto rate = find(node, "rate");
  const bool sinusoid = find(node, "amplitude") || find(node, "period") || find(node, "phase");
  if (rate && sinusoid) {
    fail(*rate, child(path, "rate") + ": a rotation takes either 'rate' (deg/s, a constant " +
                    "rate) or 'amplitude' (deg) and 'period' (s), not both");
  }
  if (rate) {
    spec.rate = kDegree * number(*rate, child(path, "rate"));
  } else if (sinusoid) {
    read_sinusoid(node, path, spec, kDegree);
  } else {
    fail(node, path + ": a rotation needs either 'rate' (deg/s) or 'amplitude' (deg) and " +
                   "'period' (s), e.g. {type: rotation, centre: [0.5, 0.1], rate: 30}");
  }
}

void MotionReader::read_file(const YAML::Node& node, const std::string& path,
                             MotionSpec& spec) const {
  const std::string quantity = choice(require(node, path, "quantity"), child(path, "quantity"),
                                      case_schema::choices(kSection, "quantity"));
  const bool angle = quantity == "angle";
  spec.quantity = angle ? MotionSpec::Quantity::Angle : MotionSpec::Quantity::Displacement;
  const std::string_view unused[] = {"direction"};
  const std::string_view unused_angle[] = {"centre", "axis"};
  for (const std::string_view key : angle ? std::span<const std::string_view>(unused)
                                          : std::span<const std::string_view>(unused_angle)) {
    if (auto v = find(node, key)) {
      fail(*v, child(path, key) + ": '" + std::string(key) +
                   "' is only used with quantity: " + (angle ? "displacement" : "angle") +
                   ", but this file gives quantity: " + quantity);
    }
  }
  if (angle) {
    read_pivot(node, path, spec);
  } else {
    read_direction(node, path, spec);
  }
  const YAML::Node file_node = require(node, path, "file");
  const std::string file = name(file_node, child(path, "file"));
  std::filesystem::path resolved(file);
  if (resolved.is_relative() && !case_dir_.empty())
    resolved = std::filesystem::path(case_dir_) / resolved;
  spec.file = resolved.string();
  try {
    std::string column;
    if (auto v = find(node, "column")) column = name(*v, child(path, "column"));
    MotionSeries series = load_motion_csv(spec.file, spec.quantity, column);
    spec.series_t = std::move(series.t);
    spec.series_value = std::move(series.value);
  } catch (const std::invalid_argument& e) {
    fail(file_node, child(path, "file") + ": " + e.what());
  }
}

// A wavemaker: the paddle, the wave and its parameters (SI; phase in degrees).
//   every wave:  paddle (piston | flap, default piston), wave (regular | solitary | focused |
//                irregular), depth (still-water depth at the paddle, m), direction (of the
//                waves, default +x), bed (vertical coordinate of the bed, default 0; the
//                vertical is the last axis); flap: hinge (the hinge point); piston:
//                absorption (active absorption, read_absorption)
//   regular:     height, period, order (1 | 2, default 1), phase (deg, default 0)
//   solitary:    height (piston only; no ramp)
//   irregular:   hs, tp, spectrum (jonswap | pm, default jonswap), gamma (3.3), components
//                (200), seed (1), f_min, f_max (Hz; default 0.5/tp and 3/tp), order (1 | 2:
//                with the bound long wave, pistons only)
//   focused:     amplitude (linear crest at the focus), focus_distance (from the paddle, m),
//                focus_time (s after the motion's start), tp, spectrum, gamma, components (60),
//                f_min, f_max, order
// The wave's time is the motion's local time (from `start`). Unless `ramp` is given, the
// paddle ramps up over 2 periods (T or Tp); a solitary wave starts from rest and takes none.
void MotionReader::read_wave(const YAML::Node& node, const std::string& path,
                             MotionSpec& spec) const {
  using waves::PaddleGeometry;
  const Names kinds = case_schema::forms(kSection, "wave");
  const std::string kind = choice(require(node, path, "wave"), child(path, "wave"), kinds);
  spec.wave_kind = kind;
  // Each wave kind's own keys (schema forms "wave:<kind>").
  std::vector<std::pair<std::string, Names>> own;
  for (const std::string_view k : kinds)
    own.emplace_back(k, case_schema::form_keys(kSection, "wave:" + std::string(k)));
  Names allowed;
  for (const auto& [k, keys] : own)
    if (k == kind) allowed = keys;
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    if (contains(allowed, key)) continue;
    Names owners;
    for (const auto& [k, keys] : own)
      if (contains(keys, key)) owners.push_back(k);
    if (owners.empty()) continue;
    fail(entry.first, child(path, key) + ": a " + kind + " wave takes no '" + key +
                          "' (it belongs to wave: " + join(owners) + "); a " + kind +
                          " wave takes " + join(allowed));
  }
  const auto number_pos = [&](const char* key) { return positive_number(node, path, key); };

  PaddleGeometry paddle;
  if (auto v = find(node, "paddle")) {
    paddle.type =
        choice(*v, child(path, "paddle"), case_schema::choices(kSection, "paddle")) == "flap"
            ? PaddleGeometry::Type::Flap
            : PaddleGeometry::Type::Piston;
  }
  const bool flap = paddle.type == PaddleGeometry::Type::Flap;
  paddle.depth = number_pos("depth");
  read_direction(node, path, spec);
  const int up = dim() - 1;  // the vertical axis
  if (std::abs(spec.direction[up]) > 1e-12) {
    fail(*find(node, "direction"), child(path, "direction") +
                                       ": waves travel horizontally; the direction must have no "
                                       "vertical (last) component");
  }
  double bed = 0.0;
  if (auto v = find(node, "bed")) bed = number(*v, child(path, "bed"));
  spec.bed = bed;
  spec.g = g_;
  if (flap) {
    spec.centre = vector(require(node, path, "hinge"), child(path, "hinge"));
    paddle.hinge_height = spec.centre[up] - bed;
    if (!(paddle.hinge_height < paddle.depth)) {
      fail(require(node, path, "hinge"),
           child(path, "hinge") + ": the flap's hinge must be below the still-water level (bed " +
               std::to_string(bed) + " + depth " + std::to_string(paddle.depth) + ")");
    }
    spec.lever = paddle.depth - paddle.hinge_height;
    Eigen::Vector3d upv = Eigen::Vector3d::Zero();
    upv[up] = 1.0;
    spec.axis = upv.cross(spec.direction).normalized();
  } else {
    if (auto v = find(node, "hinge"))
      fail(*v, child(path, "hinge") + ": 'hinge' is for a flap paddle (paddle: flap)");
  }
  if (auto v = find(node, "absorption")) {
    if (flap)
      fail(*v, child(path, "absorption") +
                   ": active absorption is implemented for pistons only (paddle: piston)");
    read_absorption(*v, child(path, "absorption"), kind, spec);
  }

  std::ostringstream label;
  label.precision(4);
  label << kind << " wave, " << (flap ? "flap" : "piston") << ", depth " << paddle.depth << " m";
  double period_for_ramp = 0.0;
  int order = 1;
  if (auto v = find(node, "order")) {
    order = integer(*v, child(path, "order"));
    expect(order == 1 || order == 2, *v, child(path, "order"), "1 or 2");
    if (order == 2 && flap)
      fail(*v, child(path, "order") +
                   ": second-order generation is implemented for pistons only; use order: "
                   "1 with a flap");
  }
  spec.wave_order = order;
  WaveRead w{node, path, kind, paddle, flap, order, label, spec};
  const auto reader = std::find_if(wave_kinds().begin(), wave_kinds().end(),
                                   [&](const WaveKind& k) { return k.name == kind; });
  if (reader == wave_kinds().end())  // choice() above took the kind from the same schema forms
    throw std::logic_error("wave kind '" + kind + "' has no reader");
  try {
    period_for_ramp = (this->*reader->read)(w);
    spec.paddle = std::make_shared<const waves::PaddleSignal>(std::move(w.signal));
  } catch (const std::invalid_argument& e) {
    fail(node, path + ": " + e.what());
  }
  if (!find(node, "ramp") && period_for_ramp > 0.0) spec.ramp = 2.0 * period_for_ramp;
  label << ", ramp " << spec.ramp << " s";
  spec.wave_label = label.str();
}

double MotionReader::read_regular(WaveRead& w) const {
  MotionSpec& spec = w.spec;
  const double h = positive_number(w.node, w.path, "height");
  const double t = positive_number(w.node, w.path, "period");
  double phase = 0.0;
  if (auto v = find(w.node, "phase")) phase = kDegree * number(*v, child(w.path, "phase"));
  w.signal = waves::regular_paddle(w.paddle, h, t, w.order, phase, g_);
  spec.wave_height = h;
  spec.wave_period = t;
  spec.wave_phase = phase;
  const waves::WaveAssessment a =
      waves::assess_regular_wave(h, t, w.paddle.depth, w.paddle, w.order, dp_, g_);
  w.label << ", H " << h << " m, T " << t << " s, order " << w.order << " (L " << a.length
          << " m, kd " << a.kd << ", " << a.theory << "; stroke " << a.stroke << " m)";
  spec.wave_notes = a.warnings;
  return t;
}

double MotionReader::read_solitary(WaveRead& w) const {
  if (w.flap) fail(w.node, w.path + ": a solitary wave (Goring 1978) needs paddle: piston");
  if (auto v = find(w.node, "ramp"))
    fail(*v, child(w.path, "ramp") + ": a solitary wave starts from rest and takes no ramp");
  const double h = positive_number(w.node, w.path, "height");
  w.signal = waves::solitary_paddle(w.paddle, h, g_);
  w.spec.wave_height = h;
  w.label << ", H " << h << " m (stroke " << w.signal.soliton.stroke << " m over "
          << w.signal.soliton.duration << " s)";
  return 0.0;
}

// The spectrum of a component set (irregular sea, focused group): its shape, peak period,
// components and frequency band.
waves::SpectrumSpec MotionReader::read_spectrum(WaveRead& w) const {
  const YAML::Node& node = w.node;
  const std::string& path = w.path;
  waves::SpectrumSpec sp;
  sp.tp = positive_number(node, path, "tp");
  if (auto v = find(node, "spectrum"))
    sp.shape =
        choice(*v, child(path, "spectrum"), case_schema::choices(kSection, "spectrum")) == "pm"
            ? waves::SpectrumSpec::Shape::PiersonMoskowitz
            : waves::SpectrumSpec::Shape::Jonswap;
  if (auto v = find(node, "gamma"))
    sp.gamma = number_if(
        *v, child(path, "gamma"), [](double g) { return g >= 1.0 && g <= 20.0; },
        "a number in [1, 20]");
  sp.components = w.kind == "focused" ? 60 : 200;
  if (auto v = find(node, "components")) {
    sp.components = integer(*v, child(path, "components"));
    expect(sp.components >= 1 && sp.components <= 5000, *v, child(path, "components"),
           "an integer in [1, 5000]");
  }
  if (auto v = find(node, "f_min")) sp.f_min = positive_number(node, path, "f_min");
  if (auto v = find(node, "f_max")) sp.f_max = positive_number(node, path, "f_max");
  const double f_lo = sp.f_min > 0 ? sp.f_min : 0.5 / sp.tp;
  const double f_hi = sp.f_max > 0 ? sp.f_max : 3.0 / sp.tp;
  if (!(f_hi > f_lo))
    fail(node, path + ": f_max (" + std::to_string(f_hi) + " Hz) must exceed f_min (" +
                   std::to_string(f_lo) + " Hz)");
  return sp;
}

// A component set (irregular sea, focused group) to first or second order. Order 2: n (n - 1) / 2
// pair terms summed every step (again for the target elevation where absorption is on).
// Measured: 200 components cost 1-4 % of the step at 15k particles
// (docs/validation/wave_bound_long.md); the cost grows as n^2, so from 500 on it is noted.
void MotionReader::component_paddle(WaveRead& w,
                                    const std::vector<waves::SurfaceComponent>& surface) const {
  w.signal = w.order == 2 ? waves::second_order_paddle(w.paddle, surface, g_)
                          : waves::linear_paddle(w.paddle, surface, g_);
}

void MotionReader::second_order_note(WaveRead& w, int n) const {
  if (w.order != 2) return;
  const long pairs = static_cast<long>(n) * (n - 1) / 2;
  w.label << ", order 2 (bound long wave, " << pairs << " pairs)";
  if (n >= 500)
    w.spec.wave_notes.push_back(
        "order 2 with " + std::to_string(n) + " components: " + std::to_string(pairs) +
        " pair terms every step (" + (w.spec.absorption ? "twice, with absorption; " : "") +
        "200 components cost 1-4 % of the step at 15k particles, and the cost grows as the "
        "square of the number of components); fewer components cost less");
}

double MotionReader::read_irregular(WaveRead& w) const {
  waves::SpectrumSpec sp = read_spectrum(w);
  sp.hs = positive_number(w.node, w.path, "hs");
  if (auto v = find(w.node, "seed")) {
    const long seed = integer(*v, child(w.path, "seed"));
    expect(seed >= 0, *v, child(w.path, "seed"), "an integer >= 0");
    sp.seed = static_cast<std::uint64_t>(seed);
  }
  component_paddle(w, waves::irregular_sea(sp));
  w.label << ", Hs " << sp.hs << " m, Tp " << sp.tp << " s, " << sp.components
          << " components, seed " << sp.seed;
  second_order_note(w, sp.components);
  return sp.tp;
}

double MotionReader::read_focused(WaveRead& w) const {
  const waves::SpectrumSpec sp = read_spectrum(w);
  const double a = positive_number(w.node, w.path, "amplitude");
  const double xf = positive_number(w.node, w.path, "focus_distance");
  const double tf = positive_number(w.node, w.path, "focus_time");
  component_paddle(w, waves::focused_group(sp, a, xf, tf, w.paddle.depth, g_));
  w.label << ", crest " << a << " m at " << xf << " m from the paddle, t " << tf << " s, Tp "
          << sp.tp << " s";
  second_order_note(w, sp.components);
  return sp.tp;
}

// absorption: true | false | {gain: tuned | shallow, distance: m, filter: s, drift: s}
// (bc/absorption.hpp). A solitary wave has no frequency to tune to: its gain is shallow.
void MotionReader::read_absorption(const YAML::Node& node, const std::string& path,
                                   const std::string& kind, MotionSpec& spec) const {
  MotionSpec::Absorption a;
  if (kind == "solitary") a.gain = MotionSpec::Absorption::Gain::Shallow;
  if (node.IsScalar()) {
    if (!boolean(node, path)) return;
    spec.absorption = a;
    return;
  }
  if (!node.IsMap())
    fail(node, path + ": expected true, false or a map {gain, distance, filter, drift}, got " +
                   describe(node));
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    if (!contains(case_schema::all_keys("bodies[].motion.absorption"), key))
      fail(entry.first, child(path, key) + ": unknown key; absorption takes gain (tuned | " +
                            "shallow), distance (m), filter (s) and drift (s)");
  }
  const auto positive = [](double v) { return v > 0.0; };
  if (auto v = find(node, "gain")) {
    const std::string g =
        choice(*v, child(path, "gain"), case_schema::choices("bodies[].motion.absorption", "gain"));
    if (g == "tuned" && kind == "solitary")
      fail(*v, child(path, "gain") + ": a solitary wave has no period to tune to; use shallow");
    a.gain =
        g == "tuned" ? MotionSpec::Absorption::Gain::Tuned : MotionSpec::Absorption::Gain::Shallow;
  }
  if (auto v = find(node, "distance"))
    a.distance = number_if(*v, child(path, "distance"), positive, "a distance > 0 m");
  if (auto v = find(node, "filter"))
    a.filter = number_if(
        *v, child(path, "filter"), [](double x) { return x >= 0.0; }, "a time >= 0 s");
  if (auto v = find(node, "drift"))
    a.drift = number_if(*v, child(path, "drift"), positive, "a time > 0 s");
  spec.absorption = a;
}

// centre (required) and axis (optional, always 3 numbers; z in 2D) of a rotation.
void MotionReader::read_pivot(const YAML::Node& node, const std::string& path,
                              MotionSpec& spec) const {
  spec.centre = vector(require(node, path, "centre"), child(path, "centre"));
  const auto v = find(node, "axis");
  if (!v) return;
  const std::string axis_path = child(path, "axis");
  spec.axis = unit(*v, axis_path, 3);
  if (dim() == 2 && (spec.axis.x() != 0.0 || spec.axis.y() != 0.0)) {
    fail(*v, axis_path +
                 ": a 2D case rotates in the xy plane, about z: expected [0, 0, 1] "
                 "(or [0, 0, -1], or leave 'axis' out), got " +
                 describe(*v));
  }
}

void MotionReader::read_direction(const YAML::Node& node, const std::string& path,
                                  MotionSpec& spec) const {
  if (auto v = find(node, "direction")) spec.direction = unit(*v, child(path, "direction"), dim());
}

// A list of `count` numbers (z = 0 when count is 2), not all zero, normalised.
Eigen::Vector3d MotionReader::unit(const YAML::Node& node, const std::string& path,
                                   int count) const {
  const std::vector<double> values = numbers(node, path, static_cast<std::size_t>(count));
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int d = 0; d < count; ++d) v[d] = values[static_cast<std::size_t>(d)];
  const double length = v.norm();
  expect(length > 0.0 && std::isfinite(length), node, path, "a non-zero vector");
  return v / length;
}

}  // namespace

MotionSpec read_motion(const NodeReader& reader, const YAML::Node& node, const std::string& path,
                       const std::string& case_dir, double g, double dp) {
  return MotionReader(reader, case_dir, g, dp).read(node, path);
}

std::vector<std::string> wave_kind_names() {
  std::vector<std::string> names;
  for (const WaveKind& k : wave_kinds()) names.emplace_back(k.name);
  return names;
}

}  // namespace swell::case_parse
