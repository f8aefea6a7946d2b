// Parsing of the top-level `gauges:` list of a case file into GaugeSpec (case/spec.hpp).
//
// Every gauge takes name, kind and every; the other keys depend on the kind, in the way the keys
// under physics.viscosity depend on the model. A key that belongs to another kind is reported as
// such ("force gauges take no 'at'"), anything else as an unknown key.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "case/parse_util.hpp"
#include "case/schema.hpp"

namespace swell::case_parse {

namespace {

struct GaugeKindInfo {
  std::string_view name;
  GaugeSpec::Kind kind;
  Names keys;  // besides the common keys
};

constexpr std::string_view kSection = "gauges[]";  // the schema's section (case/schema.cpp)

// The kinds in the schema's order, each with its keys from the schema.
const std::vector<GaugeKindInfo>& gauge_kinds() {
  static const std::vector<GaugeKindInfo> kinds = [] {
    std::vector<GaugeKindInfo> out;
    for (const std::string_view name : case_schema::forms(kSection)) {
      GaugeSpec::Kind kind{};
      bool known = false;
      for (const auto k :
           {GaugeSpec::Kind::Pressure, GaugeSpec::Kind::Height, GaugeSpec::Kind::Velocity,
            GaugeSpec::Kind::Force, GaugeSpec::Kind::Front, GaugeSpec::Kind::Runup})
        if (name == gauge_kind_name(k)) kind = k, known = true;
      if (!known) throw std::logic_error("gauge kind '" + std::string(name) + "' has no reader");
      out.push_back({name, kind, case_schema::form_keys(kSection, name)});
    }
    return out;
  }();
  return kinds;
}

bool is_name_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

class GaugeReader : private NodeReader {
 public:
  GaugeReader(const NodeReader& base, const std::vector<BodySpec>& bodies)
      : NodeReader(base), bodies_(bodies) {}

  std::vector<GaugeSpec> read_list(const YAML::Node& node, const std::string& path) const;

 private:
  GaugeSpec read_gauge(const YAML::Node& node, const std::string& path) const;
  const GaugeKindInfo& read_kind(const YAML::Node& node, const std::string& path) const;
  void check_gauge_keys(const YAML::Node& node, const std::string& path,
                        const GaugeKindInfo& kind) const;
  std::string gauge_name(const YAML::Node& node, const std::string& path) const;
  void read_pressure(const YAML::Node& node, const std::string& path, GaugeSpec& gauge) const;
  void read_force(const YAML::Node& node, const std::string& path, GaugeSpec& gauge) const;
  void read_runup(const YAML::Node& node, const std::string& path, GaugeSpec& gauge) const;

  const std::vector<BodySpec>& bodies_;
};

std::vector<GaugeSpec> GaugeReader::read_list(const YAML::Node& node,
                                              const std::string& path) const {
  expect(node.IsSequence(), node, path,
         "a list of gauges, each a map such as {name: P1, kind: pressure, at: [...]}");
  std::vector<GaugeSpec> gauges;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node gauge_node = node[i];
    GaugeSpec gauge = read_gauge(gauge_node, item(path, i));
    for (const GaugeSpec& other : gauges) {
      if (other.name != gauge.name) continue;
      fail(gauge_node["name"], item(path, i) + ".name: duplicate gauge name '" + gauge.name +
                                   "' (first used on line " + std::to_string(other.line) + ")");
    }
    gauges.push_back(std::move(gauge));
  }
  return gauges;
}

GaugeSpec GaugeReader::read_gauge(const YAML::Node& node, const std::string& path) const {
  expect(node.IsMap(), node, path, "a map such as {name: P1, kind: pressure, at: [...]}");
  GaugeSpec gauge;
  gauge.line = line_of(node);
  const GaugeKindInfo& kind = read_kind(node, path);
  gauge.kind = kind.kind;
  check_gauge_keys(node, path, kind);
  gauge.name = gauge_name(require(node, path, "name"), child(path, "name"));
  const auto positive = [](double v) { return v > 0.0; };
  if (auto v = find(node, "every")) {
    if (v->IsScalar() && v->Scalar() == "step") {
      gauge.every_step = true;
    } else {
      const bool ok = v->IsScalar() && YAML::convert<double>::decode(*v, gauge.every) &&
                      std::isfinite(gauge.every) && positive(gauge.every);
      expect(ok, *v, child(path, "every"), "a number > 0, or step (a row after every step)");
    }
  }
  switch (gauge.kind) {
    case GaugeSpec::Kind::Pressure:
      read_pressure(node, path, gauge);
      break;
    case GaugeSpec::Kind::Height:  // `at` on the floor: the vertical line starts there
      gauge.at = vector(require(node, path, "at"), child(path, "at"));
      if (auto v = find(node, "level")) {
        const std::string m = text(*v, child(path, "level"));
        expect(m == "surface" || m == "integral", *v, child(path, "level"),
               "surface (the first free surface above the start) or integral (the integral of "
               "the water fraction along the line)");
        gauge.level = m == "surface" ? GaugeSpec::Level::Surface : GaugeSpec::Level::Integral;
      }
      if (auto v = find(node, "sampling")) {
        const std::string m = text(*v, child(path, "sampling"));
        expect(m == "instant" || m == "mean", *v, child(path, "sampling"),
               "instant (the level at each row's time) or mean (the mean over each interval, "
               "evaluated every step)");
        gauge.mean = m == "mean";
      }
      break;
    case GaugeSpec::Kind::Velocity:
      gauge.at = vector(require(node, path, "at"), child(path, "at"));
      break;
    case GaugeSpec::Kind::Force:
      read_force(node, path, gauge);
      break;
    case GaugeSpec::Kind::Front:
      if (auto v = find(node, "band")) {
        gauge.band = number_if(*v, child(path, "band"), positive, "a number > 0");
      }
      break;
    case GaugeSpec::Kind::Runup:
      read_runup(node, path, gauge);
      break;
  }
  return gauge;
}

const GaugeKindInfo& GaugeReader::read_kind(const YAML::Node& node, const std::string& path) const {
  Names names;
  for (const GaugeKindInfo& info : gauge_kinds()) names.push_back(info.name);
  const std::string kind = choice(require(node, path, "kind"), child(path, "kind"), names);
  const auto& kinds = gauge_kinds();
  return *std::find_if(kinds.begin(), kinds.end(),
                       [&](const GaugeKindInfo& info) { return info.name == kind; });
}

void GaugeReader::check_gauge_keys(const YAML::Node& node, const std::string& path,
                                   const GaugeKindInfo& kind) const {
  Names allowed = case_schema::common_keys(kSection);
  allowed.insert(allowed.end(), kind.keys.begin(), kind.keys.end());
  const std::string context = " for kind " + std::string(kind.name);
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) continue;  // reported by check_keys below
    const std::string& key = entry.first.Scalar();
    if (contains(allowed, key)) continue;
    Names owners;
    for (const GaugeKindInfo& other : gauge_kinds()) {
      if (contains(other.keys, key)) owners.push_back(other.name);
    }
    if (owners.empty()) continue;  // an unknown key, reported by check_keys below
    fail(entry.first, child(path, key) + ": " + std::string(kind.name) + " gauges take no '" + key +
                          "' (it belongs to kind" + (owners.size() > 1 ? "s " : " ") +
                          join(owners) + "); allowed keys in " + path + context + ": " +
                          join(allowed));
  }
  check_keys(node, path, allowed, context);
}

std::string GaugeReader::gauge_name(const YAML::Node& node, const std::string& path) const {
  const std::string value = text(node, path);
  const bool ok = !value.empty() && std::all_of(value.begin(), value.end(), is_name_char);
  // The name becomes a CSV column and file name, hence the restricted characters.
  expect(ok, node, path, "a non-empty name of letters, digits, '_' and '-'");
  return value;
}

void GaugeReader::read_pressure(const YAML::Node& node, const std::string& path,
                                GaugeSpec& gauge) const {
  gauge.at = vector(require(node, path, "at"), child(path, "at"));
  if (auto v = find(node, "normal")) {
    const Eigen::Vector3d normal = vector(*v, child(path, "normal"));
    const double length = normal.norm();
    expect(length > 0.0, *v, child(path, "normal"), "a non-zero vector");
    gauge.normal = normal / length;
  }
  if (auto v = find(node, "offset")) {
    if (!gauge.normal) {
      fail(*v, child(path, "offset") +
                   ": 'offset' is only allowed together with 'normal' (the probe point is moved "
                   "by offset along the normal)");
    }
    gauge.offset = number_if(
        *v, child(path, "offset"), [](double o) { return o >= 0.0; }, "a number >= 0");
  }
  if (auto v = find(node, "size")) {
    if (!gauge.normal) {
      fail(*v, child(path, "size") +
                   ": 'size' (a sensor face) needs 'normal', the face's normal into the fluid");
    }
    gauge.size = number_if(
        *v, child(path, "size"), [](double d) { return d > 0.0; }, "a number > 0 [m]");
  }
}

void GaugeReader::read_force(const YAML::Node& node, const std::string& path,
                             GaugeSpec& gauge) const {
  const YAML::Node body_node = require(node, path, "body");
  gauge.body = name(body_node, child(path, "body"));
  Names boundaries;
  const BodySpec* found = nullptr;
  for (const BodySpec& body : bodies_) {
    if (body.kind == BodySpec::Kind::Boundary) boundaries.push_back(body.name);
    if (body.name == gauge.body) found = &body;
  }
  if (!found || found->kind != BodySpec::Kind::Boundary) {
    const std::string problem =
        found ? "body '" + gauge.body + "' (line " + std::to_string(found->line) +
                    ") has kind fluid, but a force gauge needs a boundary body"
              : "there is no body named '" + gauge.body + "'";
    const std::string choices = boundaries.empty() ? "the case has no boundary bodies"
                                                   : "boundary bodies: " + join(boundaries);
    fail(body_node, child(path, "body") + ": force gauge '" + gauge.name + "' (line " +
                        std::to_string(gauge.line) + "): " + problem + "; " + choices);
  }
  if (auto v = find(node, "moment_about")) {
    gauge.moment_about = vector(*v, child(path, "moment_about"));
  }
}

// The line along the slope: `from` below `to` (the vertical is the last axis), not vertical.
void GaugeReader::read_runup(const YAML::Node& node, const std::string& path,
                             GaugeSpec& gauge) const {
  const YAML::Node from_node = require(node, path, "from");
  const YAML::Node to_node = require(node, path, "to");
  gauge.from = vector(from_node, child(path, "from"));
  gauge.to = vector(to_node, child(path, "to"));
  const int up = dim() - 1;
  expect(gauge.to[up] > gauge.from[up], to_node, child(path, "to"),
         "a point higher than 'from' (the line runs up the slope from below the shoreline)");
  const Eigen::Vector3d d = gauge.to - gauge.from;
  expect(d.norm() - std::abs(d[up]) > 1e-9 * d.norm(), to_node, child(path, "to"),
         "a point beside 'from', not straight above it (the line lies along a slope)");
  gauge.at = gauge.from;  // the domain check of the case setup
  if (auto v = find(node, "swl")) gauge.swl = number(*v, child(path, "swl"));
  if (auto v = find(node, "sampling")) {
    const std::string m = text(*v, child(path, "sampling"));
    expect(m == "instant" || m == "max", *v, child(path, "sampling"),
           "instant (the runup at each row's time) or max (the largest runup within each "
           "interval, evaluated every step)");
    gauge.max = m == "max";
  }
  if (auto v = find(node, "edge"))  // the highest wet point, or the tongue attached to the sea
    gauge.connected = choice(*v, child(path, "edge"), {"highest", "connected"}) == "connected";
}

}  // namespace

std::vector<GaugeSpec> read_gauges(const NodeReader& reader, const YAML::Node& node,
                                   const std::string& path, const std::vector<BodySpec>& bodies) {
  return GaugeReader(reader, bodies).read_list(node, path);
}

}  // namespace swell::case_parse
