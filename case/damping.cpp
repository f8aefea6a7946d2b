// Parsing of the top-level `damping:` list into DampingZone (bc/damping.hpp), and of
// `time.settling` into SettlingSpec.
//
//   damping:
//     - {name: outlet, plane: {at: [8.0, 0], direction: [1, 0]}, length: 2.0,
//        ramp: quadratic, rate: 10, components: [x, y], start: 0, stop: .inf}
//     - {name: side, box: {min: [..], max: [..]}, direction: [1, 0]}
//   time: {end: 20, settling: {duration: 1.0, rate: 10}}
//
// A zone is a plane or a box (exactly one of the two keys); a plane zone takes its direction
// inside `plane` and a length, a box zone a direction beside `box` and no length (the box gives
// it). As in the gauge reader, a key that belongs to the other shape is reported as such.
#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "case/parse_util.hpp"
#include "case/schema.hpp"

namespace swell::case_parse {

namespace {

constexpr std::string_view kSection = "damping[]";  // the schema's section (case/schema.cpp)
const char* const kExample =
    "a map such as {name: outlet, plane: {at: [8, 0], direction: [1, 0]}, length: 2}";

class DampingReader : private NodeReader {
 public:
  explicit DampingReader(const NodeReader& base) : NodeReader(base) {}

  std::vector<DampingSpec> read_list(const YAML::Node& node, const std::string& path) const {
    expect(node.IsSequence(), node, path, std::string("a list of damping zones, each ") + kExample);
    std::vector<DampingSpec> zones;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node zone_node = node[i];
      DampingSpec zone = read_zone(zone_node, item(path, i));
      for (const DampingSpec& other : zones) {
        if (other.zone.name != zone.zone.name) continue;
        fail(zone_node["name"], item(path, i) + ".name: duplicate damping zone name '" +
                                    zone.zone.name + "' (first used on line " +
                                    std::to_string(other.line) + ")");
      }
      zones.push_back(std::move(zone));
    }
    return zones;
  }

  SettlingSpec read_settling(const YAML::Node& node, const std::string& path) const {
    expect_map(node, path, case_schema::all_keys("time.settling"));
    SettlingSpec s;
    s.duration = number_if(
        require(node, path, "duration"), child(path, "duration"), [](double d) { return d > 0.0; },
        "a number > 0 (seconds)");
    if (auto v = find(node, "rate")) s.rate = rate(*v, child(path, "rate"), SettlingSpec{}.rate);
    return s;
  }

 private:
  DampingSpec read_zone(const YAML::Node& node, const std::string& path) const {
    expect(node.IsMap(), node, path, kExample);
    DampingSpec spec;
    spec.line = line_of(node);
    DampingZone& z = spec.zone;
    const std::optional<YAML::Node> plane = find(node, "plane"), box = find(node, "box");
    if (plane && box)
      fail(*box, path +
                     ": a damping zone is a plane or a box, but both 'plane' and 'box' are "
                     "given");
    if (!plane && !box)
      fail(node, path +
                     ": a damping zone needs 'plane: {at: [..], direction: [..]}' (with "
                     "'length') or 'box: {min: [..], max: [..]}' (with 'direction')");
    z.shape = plane ? DampingZone::Shape::Plane : DampingZone::Shape::Box;
    check_zone_keys(node, path, z.shape);
    z.name = name(require(node, path, "name"), child(path, "name"));
    if (plane) {
      const std::string p = child(path, "plane");
      expect_map(*plane, p, case_schema::all_keys("damping[].plane"));
      z.at = vector(require(*plane, p, "at"), child(p, "at"));
      z.direction = direction(require(*plane, p, "direction"), child(p, "direction"));
      z.length = number_if(
          require(node, path, "length"), child(path, "length"), [](double l) { return l > 0.0; },
          "a number > 0 (the zone's length along its direction, m)");
    } else {
      const std::string b = child(path, "box");
      expect_map(*box, b, case_schema::all_keys("damping[].box"));
      const YAML::Node min_node = require(*box, b, "min"), max_node = require(*box, b, "max");
      z.box_min = vector(min_node, child(b, "min"));
      z.box_max = vector(max_node, child(b, "max"));
      check_ordered(z.box_min, z.box_max, min_node, max_node, b);
      z.direction = direction(require(node, path, "direction"), child(path, "direction"));
    }
    if (auto v = find(node, "ramp")) {
      const std::string r = choice(*v, child(path, "ramp"), case_schema::choices(kSection, "ramp"));
      z.ramp = r == "quadratic" ? DampingRamp::Quadratic : DampingRamp::Cosine;
    }
    if (auto v = find(node, "rate")) z.rate = rate(*v, child(path, "rate"), z.rate);
    if (auto v = find(node, "components")) z.components = components(*v, child(path, "components"));
    if (auto v = find(node, "start")) {
      z.start = number_if(
          *v, child(path, "start"), [](double t) { return t >= 0.0; }, "a number >= 0 (seconds)");
    }
    if (auto v = find(node, "stop")) {
      const double start = z.start;
      z.stop = number_if(
          *v, child(path, "stop"), [start](double t) { return t > start; },
          "a number > start (" + std::to_string(start) + " s)");
    }
    try {
      check_damping_zone(z, dim_);  // a backstop: the checks above should leave nothing
    } catch (const std::invalid_argument& e) {
      fail(node, path + ": " + e.what());
    }
    return spec;
  }

  // Keys of the other shape are named as such; anything else is an unknown key.
  void check_zone_keys(const YAML::Node& node, const std::string& path,
                       DampingZone::Shape shape) const {
    const bool is_plane = shape == DampingZone::Shape::Plane;
    const std::string_view other = is_plane ? "direction" : "length";
    if (auto v = find(node, other)) {
      fail(*v, child(path, other) +
                   (is_plane ? ": a plane zone takes its direction inside 'plane' ({at: [..], "
                               "direction: [..]})"
                             : ": a box zone takes no length (the box's extent along its "
                               "direction is the length)"));
    }
    const Names allowed = case_schema::keys_for(kSection, is_plane ? "plane" : "box");
    check_keys(node, path, allowed, is_plane ? " for a plane zone" : " for a box zone");
  }

  Eigen::Vector3d direction(const YAML::Node& node, const std::string& path) const {
    const Eigen::Vector3d v = vector(node, path);
    expect(v.norm() > 0.0 && std::isfinite(v.norm()), node, path,
           "a non-zero vector (pointing into the zone)");
    return v / v.norm();
  }

  double rate(const YAML::Node& node, const std::string& path, double fallback) const {
    return number_if(
        node, path, [](double r) { return r > 0.0; },
        "a number > 0 (the relaxation rate, 1/s; default " + number_text(fallback) + ")");
  }

  static std::string number_text(double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }

  std::array<bool, 3> components(const YAML::Node& node, const std::string& path) const {
    const Names axes = dim_ == 2 ? Names{"x", "y"} : Names{"x", "y", "z"};
    expect(node.IsSequence() && node.size() > 0, node, path,
           "a non-empty list of velocity components (" + join(axes) + ")");
    std::array<bool, 3> on = {false, false, false};
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node c = node[i];
      const std::string p = item(path, i);
      const std::string axis = choice(c, p, axes);
      const auto k = static_cast<std::size_t>(axis[0] - 'x');
      if (on[k]) fail(c, p + ": component '" + axis + "' is listed twice");
      on[k] = true;
    }
    return on;
  }
};

}  // namespace

std::vector<DampingSpec> read_damping(const NodeReader& reader, const YAML::Node& node,
                                      const std::string& path) {
  return DampingReader(reader).read_list(node, path);
}

SettlingSpec read_settling(const NodeReader& reader, const YAML::Node& node,
                           const std::string& path) {
  return DampingReader(reader).read_settling(node, path);
}

}  // namespace swell::case_parse
