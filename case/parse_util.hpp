// Internal to the case-file reader (case/reader.cpp, case/gauges.cpp, case/shapes.cpp);
// not a public API.
//
// NodeReader holds the helpers every section reader uses: key checks, typed value conversion,
// and error reporting as CaseError("<file>:<line>: <key path>: ..."). The section readers derive
// from it. Definitions live in case/reader.cpp.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "case/reader.hpp"

namespace swell::case_parse {

using Names = std::vector<std::string_view>;

std::string join(const Names& names);  // "a, b, c"
bool contains(const Names& names, std::string_view name);

// Key paths: child("physics", "rho0") == "physics.rho0", item("bodies", 1) == "bodies[1]".
inline std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}
inline std::string item(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

// 1-based line of a node; nodes built by the parser always carry a mark, others count as line 1.
int line_of(const YAML::Node& node);
// A short description of what a node holds, for "expected X, got Y" messages.
std::string describe(const YAML::Node& node);

class NodeReader {
 public:
  explicit NodeReader(std::string file) : file_(std::move(file)) {}

  // --- errors ---
  [[noreturn]] void fail(const YAML::Node& at, const std::string& message) const {
    throw CaseError(file_, line_of(at), message);
  }
  void expect(bool ok, const YAML::Node& at, const std::string& path,
              const std::string& expected) const {
    if (!ok) fail(at, path + ": expected " + expected + ", got " + describe(at));
  }

  // --- maps and keys ---
  // Fails on a key not in `allowed` or given twice; `context` follows the path in the message
  // (" for model laminar").
  void check_keys(const YAML::Node& map, const std::string& path, const Names& allowed,
                  const std::string& context = "") const;
  void expect_map(const YAML::Node& node, const std::string& path, const Names& allowed) const {
    expect(node.IsMap(), node, path, "a map with keys " + join(allowed));
    check_keys(node, path, allowed);
  }
  static std::optional<YAML::Node> find(const YAML::Node& map, std::string_view key) {
    const YAML::Node value = map[std::string(key)];
    if (!value.IsDefined()) return std::nullopt;
    return value;
  }
  YAML::Node require(const YAML::Node& map, const std::string& path, std::string_view key) const {
    std::optional<YAML::Node> value = find(map, key);
    if (!value) fail(map, "missing required key '" + child(path, key) + "'");
    return *value;
  }

  // --- typed values ---
  double number(const YAML::Node& node, const std::string& path) const;
  int integer(const YAML::Node& node, const std::string& path) const;
  bool boolean(const YAML::Node& node, const std::string& path) const;
  std::string text(const YAML::Node& node, const std::string& path) const;
  std::string name(const YAML::Node& node, const std::string& path) const;
  std::string choice(const YAML::Node& node, const std::string& path, const Names& allowed) const;
  std::vector<double> numbers(const YAML::Node& node, const std::string& path,
                              std::size_t count) const;
  // A list of `dim` numbers; z stays 0 in 2D.
  Eigen::Vector3d vector(const YAML::Node& node, const std::string& path) const;
  // A number that must satisfy `ok`; `expected` describes the condition ("a number > 0").
  template <class Predicate>
  double number_if(const YAML::Node& node, const std::string& path, Predicate ok,
                   const std::string& expected) const {
    const double value = number(node, path);
    expect(ok(value), node, path, expected);
    return value;
  }
  // Checks min < max on each of the first `dim` axes; `max_node` is where a failure is reported.
  void check_ordered(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                     const YAML::Node& min_node, const YAML::Node& max_node,
                     const std::string& path) const;
  int dim() const { return dim_; }

 protected:
  std::string file_;
  int dim_ = 2;  // set from the top-level `dim` before anything dimension-dependent
};

// Reads the top-level `gauges` list (case/gauges.cpp). `reader` supplies the file label and
// dimension; force gauges are checked against `bodies`.
// Reads a shape (case/shapes.cpp): a map with exactly one key naming its kind (box, cylinder,
// sphere, polygon, mesh or its synonym stl, union, difference); union and difference take a list
// of shapes, read recursively. `reader` supplies the file label and dimension.
ShapeSpec read_shape(const NodeReader& reader, const YAML::Node& node, const std::string& path);

std::vector<GaugeSpec> read_gauges(const NodeReader& reader, const YAML::Node& node,
                                   const std::string& path, const std::vector<BodySpec>& bodies);

// Reads the top-level `damping` list (case/damping.cpp): plane and box zones, checked.
std::vector<DampingSpec> read_damping(const NodeReader& reader, const YAML::Node& node,
                                      const std::string& path);
// Reads `time.settling` (case/damping.cpp): {duration: T, rate: sigma_0}.
SettlingSpec read_settling(const NodeReader& reader, const YAML::Node& node,
                           const std::string& path);

}  // namespace swell::case_parse
