// Parsing and validation of YAML case files (see case/reader.hpp and
// docs/user-guide/case-files.md).
//
// The reader walks the YAML tree section by section. Each map is first checked against its list
// of allowed keys, so a misspelt key is an error rather than a silently ignored setting; then
// each value is converted by a small typed helper that names the key path in its message. The
// helpers (NodeReader) are shared with the shape reader, case/shapes.cpp, and the gauge
// reader, case/gauges.cpp, through case/parse_util.hpp.
#include "case/reader.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "case/model_names.hpp"
#include "case/motion.hpp"
#include "case/parse_util.hpp"
#include "case/safe_name.hpp"
#include "case/schema.hpp"

namespace swell {

namespace case_parse {

namespace {

// Quoted scalars ('1.0') carry the tag "!"; only plain scalars are read as numbers or booleans.
bool is_plain_scalar(const YAML::Node& node) {
  return node.IsScalar() && node.Tag() != "!";
}

// Short lists of plain scalars are shown as written, e.g. [0, 0, -9.81].
std::optional<std::string> short_list(const YAML::Node& node) {
  if (node.size() > 6) return std::nullopt;
  std::string out = "[";
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node element = node[i];
    if (!is_plain_scalar(element)) return std::nullopt;
    out += (i > 0 ? ", " : "") + element.Scalar();
  }
  return out + "]";
}

}  // namespace

std::string join(const Names& names) {
  std::string out;
  for (const std::string_view name : names) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

bool contains(const Names& names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

int line_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 1 : mark.line + 1;
}

// A scalar as it can be shown in a message: control characters (a NUL would end the message
// where it is printed) as \xHH, and at most 200 characters.
std::string printable(const std::string& s) {
  std::string out;
  for (const char c : s.substr(0, 200)) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    } else {
      out += c;
    }
  }
  if (s.size() > 200) out += "...";
  return out;
}

std::string describe(const YAML::Node& node) {
  if (is_plain_scalar(node)) return "'" + printable(node.Scalar()) + "'";
  if (node.IsScalar()) return "the quoted string '" + printable(node.Scalar()) + "'";
  if (node.IsSequence()) {
    if (auto shown = short_list(node)) return *shown;
    return "a list of " + std::to_string(node.size()) + (node.size() == 1 ? " item" : " items");
  }
  if (node.IsMap()) return "a map with " + std::to_string(node.size()) + " keys";
  return "an empty value";
}

// ---------------------------------------------------------------------------------------------
// Maps and typed values

void NodeReader::check_keys(const YAML::Node& map, const std::string& path, const Names& allowed,
                            const std::string& context) const {
  const std::string where = path.empty() ? "" : " in " + path + context;
  std::set<std::string> seen;
  for (const auto& entry : map) {
    const YAML::Node& key = entry.first;
    if (!key.IsScalar()) fail(key, "keys" + where + " must be plain names, got " + describe(key));
    const std::string& k = key.Scalar();
    if (!contains(allowed, k)) {
      fail(key,
           "unknown key '" + child(path, k) + "'; allowed keys" + where + ": " + join(allowed));
    }
    if (!seen.insert(k).second) fail(key, "duplicate key '" + child(path, k) + "'");
  }
}

double NodeReader::number(const YAML::Node& node, const std::string& path) const {
  double value = 0.0;
  const bool ok =
      is_plain_scalar(node) && YAML::convert<double>::decode(node, value) && std::isfinite(value);
  expect(ok, node, path, "a number");
  return value;
}

int NodeReader::integer(const YAML::Node& node, const std::string& path) const {
  int value = 0;
  const bool ok = is_plain_scalar(node) && YAML::convert<int>::decode(node, value);
  expect(ok, node, path, "an integer");
  return value;
}

bool NodeReader::boolean(const YAML::Node& node, const std::string& path) const {
  bool value = false;
  const bool ok = is_plain_scalar(node) && YAML::convert<bool>::decode(node, value);
  expect(ok, node, path, "true or false");
  return value;
}

std::string NodeReader::text(const YAML::Node& node, const std::string& path) const {
  expect(node.IsScalar(), node, path, "a string");
  return node.Scalar();
}

std::string NodeReader::name(const YAML::Node& node, const std::string& path) const {
  const std::string value = text(node, path);
  const bool blank = value.find_first_not_of(" \t") == std::string::npos;
  expect(!blank, node, path, "a non-empty name");
  return value;
}

std::string NodeReader::choice(const YAML::Node& node, const std::string& path,
                               const Names& allowed) const {
  const std::string value = text(node, path);
  if (!contains(allowed, value)) {
    fail(node, path + ": unknown value '" + value + "'; expected one of: " + join(allowed));
  }
  return value;
}

std::vector<double> NodeReader::numbers(const YAML::Node& node, const std::string& path,
                                        std::size_t count) const {
  const std::string expected = "a list of " + std::to_string(count) + " numbers";
  expect(node.IsSequence() && node.size() == count, node, path, expected);
  std::vector<double> values;
  for (std::size_t i = 0; i < count; ++i) {
    const YAML::Node element = node[i];
    double value = 0.0;
    if (!is_plain_scalar(element) || !YAML::convert<double>::decode(element, value) ||
        !std::isfinite(value)) {
      fail(element, path + ": expected " + expected + ", but item " + std::to_string(i) + " is " +
                        describe(element));
    }
    values.push_back(value);
  }
  return values;
}

Eigen::Vector3d NodeReader::vector(const YAML::Node& node, const std::string& path) const {
  const std::vector<double> values = numbers(node, path, static_cast<std::size_t>(dim_));
  Eigen::Vector3d v = Eigen::Vector3d::Zero();  // z stays 0 in 2D
  for (int d = 0; d < dim_; ++d) v[d] = values[static_cast<std::size_t>(d)];
  return v;
}

void NodeReader::check_ordered(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                               const YAML::Node& min_node, const YAML::Node& max_node,
                               const std::string& path) const {
  static const char* const kAxes[] = {"x", "y", "z"};
  for (int d = 0; d < dim_; ++d) {
    if (min[d] < max[d]) continue;
    const auto i = static_cast<std::size_t>(d);
    fail(max_node, path + ": expected min < max on every axis, but on " + kAxes[d] +
                       " min = " + min_node[i].Scalar() + " and max = " + max_node[i].Scalar());
  }
}

// ---------------------------------------------------------------------------------------------
// Sections

namespace {

class CaseReader : private NodeReader {
 public:
  explicit CaseReader(std::string file) : NodeReader(std::move(file)) {}

  CaseSpec read(const YAML::Node& root);

 private:
  // --- sections ---
  void read_physics(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_viscosity(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_diffusion(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_boundary(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_shifting(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_corrections(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_density_bounds(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_time(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_domain(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_output(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_watchdog(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  void read_limits(const YAML::Node& node, const std::string& path, CaseSpec& spec) const;
  std::vector<BodySpec> read_bodies(const YAML::Node& node, const std::string& path) const;
  BodySpec read_body(const YAML::Node& node, const std::string& path) const;
  void read_wall_options(const YAML::Node& node, const std::string& path, BodySpec& body) const;
  void read_fill(const YAML::Node& node, const std::string& path, BodySpec& body) const;
  void resolve_fill_targets(const YAML::Node& node, const std::string& path,
                            std::vector<BodySpec>& bodies) const;
  std::vector<std::string> read_open_faces(const YAML::Node& node, const std::string& path) const;

  // One of `values` given by its name (`name_of`, case/model_names.hpp); fails listing the names.
  template <class Enum, std::size_t N>
  Enum model(const YAML::Node& node, const std::string& path, const std::array<Enum, N>& values,
             const char* (*name_of)(Enum)) const {
    Names names;
    for (const Enum v : values) names.push_back(name_of(v));
    const std::string chosen = choice(node, path, names);
    for (const Enum v : values)
      if (chosen == name_of(v)) return v;
    return values[0];  // not reached: choice() accepts only the names of `values`
  }

  double g_ = 9.81;  // |gravity|, set after the physics section (wavemakers' dispersion)
  double dp_ = 0.0;  // the particle spacing (wavemakers' resolution checks)
};

CaseSpec CaseReader::read(const YAML::Node& root) {
  const Names top_keys = case_schema::all_keys("");
  expect(root.IsMap(), root, "case file", "a map with keys " + join(top_keys));
  check_keys(root, "", top_keys);

  CaseSpec spec;
  const YAML::Node dim_node = require(root, "", "dim");
  spec.dim = integer(dim_node, "dim");
  expect(spec.dim == 2 || spec.dim == 3, dim_node, "dim", "2 or 3");
  dim_ = spec.dim;
  if (spec.dim == 3) spec.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);

  spec.dp = number_if(
      require(root, "", "dp"), "dp", [](double v) { return v > 0.0; }, "a number > 0");
  if (auto node = find(root, "name")) {
    spec.name = name(*node, "name");
    expect(is_safe_name(spec.name), *node, "name", safe_name_rule());
  }
  if (auto node = find(root, "physics")) read_physics(*node, "physics", spec);
  g_ = spec.gravity.norm();
  dp_ = spec.dp;
  read_time(require(root, "", "time"), "time", spec);
  if (auto node = find(root, "domain")) read_domain(*node, "domain", spec);
  spec.bodies = read_bodies(require(root, "", "bodies"), "bodies");
  if (auto node = find(root, "gauges")) {
    spec.gauges = read_gauges(*this, *node, "gauges", spec.bodies);
  }
  if (auto node = find(root, "damping")) spec.damping = read_damping(*this, *node, "damping");
  if (auto node = find(root, "output")) read_output(*node, "output", spec);
  if (auto node = find(root, "watchdog")) read_watchdog(*node, "watchdog", spec);
  if (auto node = find(root, "limits")) read_limits(*node, "limits", spec);
  return spec;
}

void CaseReader::read_physics(const YAML::Node& node, const std::string& path,
                              CaseSpec& spec) const {
  expect_map(node, path, case_schema::all_keys("physics"));
  const auto positive = [](double v) { return v > 0.0; };
  if (auto v = find(node, "rho0")) {
    spec.rho0 = number_if(*v, child(path, "rho0"), positive, "a number > 0");
  }
  if (auto v = find(node, "gravity")) {
    spec.gravity = vector(*v, child(path, "gravity"));
    // c0 = coefsound sqrt(|g| hswl): without gravity the speed of sound, hence dt, is zero.
    expect(spec.gravity.norm() > 0.0, *v, child(path, "gravity"),
           "a non-zero vector (c0 = coefsound sqrt(|g| hswl) needs gravity)");
  }
  if (auto v = find(node, "coefsound")) {
    spec.coefsound = number_if(*v, child(path, "coefsound"), positive, "a number > 0");
  }
  if (auto v = find(node, "coefh")) {
    // h = coefh sqrt(D) dp; outside [0.5, 4] a particle has ~2 or ~800 neighbours (3D).
    spec.coefh = number_if(
        *v, child(path, "coefh"), [](double c) { return c >= 0.5 && c <= 4.0; },
        "a number in [0.5, 4] (DualSPHysics cases use 0.75-1.5)");
  }
  if (auto v = find(node, "hswl")) {
    spec.hswl = number_if(*v, child(path, "hswl"), positive, "a number > 0");
  }
  if (auto v = find(node, "kernel")) {
    spec.kernel = model(*v, child(path, "kernel"), kKernelTypes, kernel_name);
  }
  if (auto v = find(node, "viscosity")) read_viscosity(*v, child(path, "viscosity"), spec);
  if (auto v = find(node, "density_diffusion")) {
    read_diffusion(*v, child(path, "density_diffusion"), spec);
  }
  if (auto v = find(node, "density_bounds")) {
    read_density_bounds(*v, child(path, "density_bounds"), spec);
  }
  if (auto v = find(node, "boundary")) read_boundary(*v, child(path, "boundary"), spec);
  if (auto v = find(node, "shifting")) read_shifting(*v, child(path, "shifting"), spec);
  if (auto v = find(node, "corrections")) read_corrections(*v, child(path, "corrections"), spec);
  if (spec.kernel_gradient_correction && spec.viscosity_model == ViscosityModel::Laminar) {
    const YAML::Node c = *find(node, "corrections");
    expect(false, c, child(path, "corrections"),
           "kernel_gradient: none with laminar viscosity (the corrected gradient applies to the "
           "pressure and artificial-viscosity sum only)");
  }
}

// `corrections: {kernel_gradient: none|kgc, det_min: 0.1, shepard_reinit: 0}`.
void CaseReader::read_corrections(const YAML::Node& node, const std::string& path,
                                  CaseSpec& spec) const {
  expect_map(node, path, case_schema::all_keys("physics.corrections"));
  if (auto v = find(node, "kernel_gradient")) {
    spec.kernel_gradient_correction =
        choice(*v, child(path, "kernel_gradient"), {"none", "kgc"}) == "kgc";
  }
  if (auto v = find(node, "det_min")) {
    spec.kgc_det_min = number_if(
        *v, child(path, "det_min"), [](double d) { return d > 0.0 && d < 1.0; },
        "a number in (0, 1)");
  }
  if (auto v = find(node, "shepard_reinit")) {
    spec.shepard_reinit = integer(*v, child(path, "shepard_reinit"));
    expect(spec.shepard_reinit >= 0, *v, child(path, "shepard_reinit"),
           "an integer >= 0 (steps; 0: never)");
  }
}

// `shifting: {model: none}` or `{model: fickian, coefficient: 2, surface_threshold: 1.5}`.
void CaseReader::read_shifting(const YAML::Node& node, const std::string& path,
                               CaseSpec& spec) const {
  expect(node.IsMap(), node, path, "a map such as {model: fickian}");
  if (auto v = find(node, "model")) {
    spec.shifting = model(*v, child(path, "model"), kShiftingModels, shifting_name);
  }
  if (spec.shifting == ShiftingModel::None) {
    check_keys(node, path, case_schema::keys_for("physics.shifting", "none"), " for model none");
    return;
  }
  check_keys(node, path, case_schema::keys_for("physics.shifting", "fickian"),
             " for model fickian");
  if (auto v = find(node, "coefficient")) {
    // Skillen et al. (2013) and DualSPHysics use 2; beyond ~10 the shift per step is no longer
    // small against dp.
    spec.shift_coefficient = number_if(
        *v, child(path, "coefficient"), [](double a) { return a > 0.0 && a <= 10.0; },
        "a number in (0, 10] (default 2)");
  }
  if (auto v = find(node, "surface_threshold")) {
    // div r is ~dim inside the fluid and ~dim/2 on a flat surface.
    const double dim = spec.dim;
    spec.shift_surface_threshold = number_if(
        *v, child(path, "surface_threshold"), [dim](double t) { return t > 0.0 && t < dim; },
        "a number in (0, dim) (default 1.5 in 2D, 2.75 in 3D)");
  }
  if (auto v = find(node, "correct_density"))
    spec.shift_correct_density = boolean(*v, child(path, "correct_density"));
  if (auto v = find(node, "mode"))
    spec.shift_mode = model(*v, child(path, "mode"), kShiftModes, shift_mode_name);
}

// `boundary: {model: dbc}` or
// `{model: mdbc, slip: wall|noslip|freeslip, pressure: linear|hydrostatic, det_min: 1e-3}`.
void CaseReader::read_boundary(const YAML::Node& node, const std::string& path,
                               CaseSpec& spec) const {
  expect(node.IsMap(), node, path, "a map such as {model: mdbc, slip: noslip}");
  if (auto v = find(node, "model")) {
    spec.boundary = model(*v, child(path, "model"), kBoundaryTypes, boundary_name);
  }
  if (spec.boundary == BoundaryType::Dbc) {
    check_keys(node, path, case_schema::keys_for("physics.boundary", "dbc"), " for model dbc");
    return;
  }
  check_keys(node, path, case_schema::keys_for("physics.boundary", "mdbc"), " for model mdbc");
  if (auto v = find(node, "slip")) {
    spec.mdbc_slip = model(*v, child(path, "slip"), kMdbcSlips, mdbc_slip_name);
  }
  if (auto v = find(node, "pressure")) {
    spec.mdbc_pressure = model(*v, child(path, "pressure"), kMdbcPressures, mdbc_pressure_name);
  }
  if (auto v = find(node, "det_min")) {
    spec.mdbc_det_min = number_if(
        *v, child(path, "det_min"), [](double d) { return d > 0.0 && d < 1.0; },
        "a number in (0, 1)");
  }
}

// The allowed keys depend on the model: `alpha` belongs to artificial viscosity, `nu` to laminar.
void CaseReader::read_viscosity(const YAML::Node& node, const std::string& path,
                                CaseSpec& spec) const {
  expect(node.IsMap(), node, path, "a map such as {model: artificial, alpha: 0.01}");
  if (auto v = find(node, "model")) {
    spec.viscosity_model = model(*v, child(path, "model"), kViscosityModels, viscosity_name);
  }
  const auto non_negative = [](double v) { return v >= 0.0; };
  if (spec.viscosity_model == ViscosityModel::Artificial) {
    check_keys(node, path, case_schema::keys_for("physics.viscosity", "artificial"),
               " for model artificial");
    if (auto v = find(node, "alpha")) {
      spec.alpha = number_if(*v, child(path, "alpha"), non_negative, "a number >= 0");
    }
  } else {
    check_keys(node, path, case_schema::keys_for("physics.viscosity", "laminar"),
               " for model laminar");
    if (auto v = find(node, "nu")) {
      spec.nu = number_if(*v, child(path, "nu"), non_negative, "a number >= 0");
    }
  }
}

void CaseReader::read_diffusion(const YAML::Node& node, const std::string& path,
                                CaseSpec& spec) const {
  expect(node.IsMap(), node, path, "a map such as {model: fourtakas, delta: 0.1}");
  if (auto v = find(node, "model")) {
    spec.diffusion_model = model(*v, child(path, "model"), kDiffusionModels, diffusion_name);
  }
  if (spec.diffusion_model == DiffusionModel::None) {
    check_keys(node, path, case_schema::keys_for("physics.density_diffusion", "none"),
               " for model none");
    return;
  }
  const std::string diffusion = diffusion_name(spec.diffusion_model);
  check_keys(node, path, case_schema::keys_for("physics.density_diffusion", diffusion),
             " for model " + diffusion);
  if (auto v = find(node, "delta")) {
    spec.delta = number_if(
        *v, child(path, "delta"), [](double d) { return d >= 0.0; }, "a number >= 0");
  }
}

void CaseReader::read_density_bounds(const YAML::Node& node, const std::string& path,
                                     CaseSpec& spec) const {
  const std::vector<double> bounds = numbers(node, path, 2);
  const bool ok = bounds[0] > 0.0 && bounds[0] <= 1.0 && bounds[1] >= 1.0 && bounds[0] < bounds[1];
  expect(ok, node, path, "[min, max] factors of rho0 with 0 < min <= 1 <= max and min < max");
  spec.rho_min_factor = bounds[0];
  spec.rho_max_factor = bounds[1];
}

void CaseReader::read_time(const YAML::Node& node, const std::string& path, CaseSpec& spec) const {
  expect_map(node, path, case_schema::all_keys("time"));
  spec.t_end = number_if(
      require(node, path, "end"), child(path, "end"), [](double v) { return v > 0.0; },
      "a number > 0");
  if (auto v = find(node, "cfl")) {
    spec.cfl = number_if(
        *v, child(path, "cfl"), [](double c) { return c > 0.0 && c <= 1.0; }, "a number in (0, 1]");
  }
  if (auto v = find(node, "dt_fixed")) {
    spec.dt_fixed = number_if(
        *v, child(path, "dt_fixed"), [](double d) { return d > 0.0; }, "a number > 0");
  }
  if (auto v = find(node, "integrator")) {
    spec.integrator = model(*v, child(path, "integrator"), kIntegratorTypes, integrator_name);
  }
  if (auto v = find(node, "verlet_steps")) {
    spec.verlet_steps = integer(*v, child(path, "verlet_steps"));
    expect(spec.verlet_steps >= 1, *v, child(path, "verlet_steps"), "an integer >= 1");
  }
  if (auto v = find(node, "settling"))
    spec.settling = read_settling(*this, *v, child(path, "settling"));
}

void CaseReader::read_domain(const YAML::Node& node, const std::string& path,
                             CaseSpec& spec) const {
  expect_map(node, path, case_schema::all_keys("domain"));
  const YAML::Node min_node = require(node, path, "min");
  const YAML::Node max_node = require(node, path, "max");
  const Eigen::Vector3d min = vector(min_node, child(path, "min"));
  const Eigen::Vector3d max = vector(max_node, child(path, "max"));
  check_ordered(min, max, min_node, max_node, path);
  spec.domain_min = min;
  spec.domain_max = max;
  if (auto v = find(node, "periodic")) {
    const std::string ppath = child(path, "periodic");
    const Names axes = dim_ == 2 ? Names{"x", "y"} : Names{"x", "y", "z"};
    expect(v->IsSequence(), *v, ppath, "a list of axes (" + join(axes) + ")");
    for (std::size_t i = 0; i < v->size(); ++i) {
      const YAML::Node a = (*v)[i];
      const std::string apath = item(ppath, i);
      const std::string axis = text(a, apath);
      if (dim_ == 2 && axis == "z")
        fail(a, apath + ": axis 'z' does not exist in a 2D case; expected one of: " + join(axes));
      choice(a, apath, axes);
      const auto d = static_cast<std::size_t>(axis[0] - 'x');
      if (spec.periodic[d]) fail(a, apath + ": axis '" + axis + "' is listed twice");
      spec.periodic[d] = true;
    }
  }
}

void CaseReader::read_output(const YAML::Node& node, const std::string& path,
                             CaseSpec& spec) const {
  expect_map(node, path, case_schema::all_keys("output"));
  const auto non_negative = [](double e) { return e >= 0.0; };
  if (auto v = find(node, "every")) {
    spec.output_every = number_if(*v, child(path, "every"), non_negative, "a number >= 0");
  }
  if (auto v = find(node, "vtk")) spec.vtk = boolean(*v, child(path, "vtk"));
  if (auto v = find(node, "vtk_split")) spec.vtk_split = boolean(*v, child(path, "vtk_split"));
  if (auto v = find(node, "hdf5")) spec.hdf5 = boolean(*v, child(path, "hdf5"));
  if (auto v = find(node, "checkpoint_every")) {
    spec.checkpoint_every =
        number_if(*v, child(path, "checkpoint_every"), non_negative, "a number >= 0");
  }
  if (auto v = find(node, "gauge_every")) {
    spec.gauge_every = number_if(
        *v, child(path, "gauge_every"), [](double e) { return e > 0.0; }, "a number > 0");
  }
}

// Thresholds of the blow-up watchdog (solver/diagnostics.hpp, WatchdogLimits).
void CaseReader::read_watchdog(const YAML::Node& node, const std::string& path,
                               CaseSpec& spec) const {
  expect_map(node, path, case_schema::all_keys("watchdog"));
  WatchdogLimits& w = spec.watchdog;
  const auto fraction = [](double f) { return f > 0.0 && f <= 1.0; };
  if (auto v = find(node, "every")) {
    w.every = integer(*v, child(path, "every"));
    expect(w.every >= 1 && w.every <= 1000, *v, child(path, "every"),
           "an integer in [1, 1000] (steps)");
  }
  if (auto v = find(node, "warn_excluded")) {
    w.warn_excluded_fraction =
        number_if(*v, child(path, "warn_excluded"), fraction, "a fraction in (0, 1]");
  }
  if (auto v = find(node, "max_excluded")) {
    w.max_excluded_fraction =
        number_if(*v, child(path, "max_excluded"), fraction, "a fraction in (0, 1]");
  }
  if (auto v = find(node, "max_density")) {
    w.max_density_factor = number_if(
        *v, child(path, "max_density"), [](double f) { return f > 1.0; }, "a factor of rho0 > 1");
  }
  if (auto v = find(node, "penetration_depth")) {
    w.penetration_depth = number_if(
        *v, child(path, "penetration_depth"), [](double d) { return d > 0.0; },
        "a number of dp > 0");
  }
  if (auto v = find(node, "max_penetrated")) {
    w.max_penetrated_fraction = number_if(
        *v, child(path, "max_penetrated"), [](double f) { return f >= 0.0 && f <= 1.0; },
        "a fraction in [0, 1]");
  }
  if (auto v = find(node, "dt_collapse")) {
    spec.dt_collapse = number_if(
        *v, child(path, "dt_collapse"), [](double f) { return f > 0.0 && f < 1.0; },
        "a fraction of the first dt in (0, 1)");
  }
}

void CaseReader::read_limits(const YAML::Node& node, const std::string& path,
                             CaseSpec& spec) const {
  expect_map(node, path, case_schema::all_keys("limits"));
  if (auto v = find(node, "max_particles")) {
    spec.max_particles = number_if(
        *v, child(path, "max_particles"), [](double n) { return n >= 1.0; }, "a number >= 1");
  }
}

// ---------------------------------------------------------------------------------------------
// Bodies

std::vector<BodySpec> CaseReader::read_bodies(const YAML::Node& node,
                                              const std::string& path) const {
  expect(node.IsSequence() && node.size() > 0, node, path, "a non-empty list of bodies");
  std::vector<BodySpec> bodies;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node body_node = node[i];
    BodySpec body = read_body(body_node, item(path, i));
    for (const BodySpec& other : bodies) {
      if (other.name != body.name) continue;
      fail(body_node["name"], item(path, i) + ".name: duplicate body name '" + body.name +
                                  "' (first used on line " + std::to_string(other.line) + ")");
    }
    bodies.push_back(std::move(body));
  }
  const bool has_fluid = std::any_of(bodies.begin(), bodies.end(), [](const BodySpec& b) {
    return b.kind == BodySpec::Kind::Fluid;
  });
  if (!has_fluid) fail(node, path + ": no fluid body; at least one body needs 'kind: fluid'");
  resolve_fill_targets(node, path, bodies);
  return bodies;
}

BodySpec CaseReader::read_body(const YAML::Node& node, const std::string& path) const {
  expect_map(node, path, case_schema::all_keys("bodies[]"));
  BodySpec body;
  body.line = line_of(node);
  body.name = name(require(node, path, "name"), child(path, "name"));
  const std::string kind = choice(require(node, path, "kind"), child(path, "kind"),
                                  case_schema::choices("bodies[]", "kind"));
  body.kind = kind == "fluid" ? BodySpec::Kind::Fluid : BodySpec::Kind::Boundary;
  // A fluid body is a shape or a fill of a tank; a boundary body is always a shape.
  const std::optional<YAML::Node> shape = find(node, "shape");
  const std::optional<YAML::Node> fill = find(node, "fill");
  if (body.kind == BodySpec::Kind::Boundary) {
    if (fill) {
      fail(*fill, child(path, "fill") + ": only fluid bodies take 'fill', but body '" + body.name +
                      "' has kind boundary");
    }
    body.shape = case_parse::read_shape(*this, require(node, path, "shape"), child(path, "shape"));
  } else if (shape && fill) {
    fail(*fill, child(path, "fill") + ": body '" + body.name +
                    "' gives both 'shape' and 'fill'; a fluid body takes exactly one of them");
  } else if (fill) {
    read_fill(*fill, child(path, "fill"), body);
  } else if (shape) {
    body.shape = case_parse::read_shape(*this, *shape, child(path, "shape"));
  } else {
    fail(node, "missing required key '" + child(path, "shape") + "' (or '" + child(path, "fill") +
                   "': a fluid body is a shape, or a fill such as {below: 0.3, inside: tank})");
  }
  read_wall_options(node, path, body);
  return body;
}

// `fill: {below: LEVEL, inside: BODY}`; BODY is resolved once every body is known
// (resolve_fill_targets), since it may come later in the list.
void CaseReader::read_fill(const YAML::Node& node, const std::string& path, BodySpec& body) const {
  expect(node.IsMap(), node, path, "a map such as {below: 0.3, inside: tank}");
  check_keys(node, path, case_schema::all_keys("bodies[].fill"));
  body.fill_below = number(require(node, path, "below"), child(path, "below"));
  body.fill_inside = name(require(node, path, "inside"), child(path, "inside"));
}

// Every fill must name a boundary body with `walls: inside` (a tank the water can fill); its
// index is stored in BodySpec::fill_container, the only place a fill's target is looked up.
void CaseReader::resolve_fill_targets(const YAML::Node& node, const std::string& path,
                                      std::vector<BodySpec>& bodies) const {
  Names tanks;
  for (const BodySpec& body : bodies) {
    if (body.kind == BodySpec::Kind::Boundary && body.walls == BodySpec::Walls::Inside) {
      tanks.push_back(body.name);
    }
  }
  const std::string choices = tanks.empty() ? "the case has no boundary body with walls: inside"
                                            : "boundary bodies with walls: inside: " + join(tanks);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    BodySpec& body = bodies[i];
    if (!body.fill_below) continue;
    const auto target = std::find_if(bodies.begin(), bodies.end(),
                                     [&](const BodySpec& b) { return b.name == body.fill_inside; });
    std::string problem;
    if (target == bodies.end()) {
      problem = "there is no body named '" + body.fill_inside + "'";
    } else if (target->kind == BodySpec::Kind::Fluid) {
      problem =
          "body '" + target->name + "' (line " + std::to_string(target->line) + ") has kind fluid";
    } else if (target->walls != BodySpec::Walls::Inside) {
      problem = "body '" + target->name + "' (line " + std::to_string(target->line) +
                ") has walls: outside (a solid structure)";
    } else {
      body.fill_container = static_cast<int>(target - bodies.begin());
      continue;
    }
    const std::string inside_path = child(child(item(path, i), "fill"), "inside");
    fail(node[i]["fill"]["inside"],
         inside_path + ": fluid body '" + body.name + "' fills the inside of '" + body.fill_inside +
             "', but " + problem + "; a fill needs a boundary body with walls: inside (" + choices +
             ")");
  }
}

// walls, layers and open describe wall particles, so only boundary bodies take them.
void CaseReader::read_wall_options(const YAML::Node& node, const std::string& path,
                                   BodySpec& body) const {
  if (body.kind == BodySpec::Kind::Fluid) {
    for (const std::string_view key : case_schema::form_keys("bodies[]", "boundary")) {
      if (auto v = find(node, key)) {
        fail(*v, child(path, key) + ": only boundary bodies take '" + std::string(key) +
                     "', but body '" + body.name + "' has kind fluid");
      }
    }
    return;
  }
  if (auto v = find(node, "walls")) {
    const std::string walls =
        choice(*v, child(path, "walls"), case_schema::choices("bodies[]", "walls"));
    body.walls = walls == "inside" ? BodySpec::Walls::Inside : BodySpec::Walls::Outside;
  }
  if (auto v = find(node, "layers")) {
    body.layers = integer(*v, child(path, "layers"));
    expect(body.layers >= 1, *v, child(path, "layers"), "an integer >= 1");
  }
  if (auto v = find(node, "open")) body.open = read_open_faces(*v, child(path, "open"));
  if (auto v = find(node, "boundary")) {
    const std::string m =
        choice(*v, child(path, "boundary"), case_schema::choices("bodies[]", "boundary"));
    body.boundary = m == "mdbc" ? BoundaryType::Mdbc : BoundaryType::Dbc;
  }
  if (auto v = find(node, "motion"))
    body.motion = read_motion(*this, *v, child(path, "motion"),
                              std::filesystem::path(file_).parent_path().string(), g_, dp_);
}

std::vector<std::string> CaseReader::read_open_faces(const YAML::Node& node,
                                                     const std::string& path) const {
  const Names faces = dim_ == 2 ? Names{"xmin", "xmax", "ymin", "ymax"}
                                : Names{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  expect(node.IsSequence(), node, path, "a list of faces (" + join(faces) + ")");
  std::vector<std::string> open;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node face_node = node[i];
    const std::string face_path = item(path, i);
    const std::string face = text(face_node, face_path);
    if (dim_ == 2 && (face == "zmin" || face == "zmax")) {
      fail(face_node, face_path + ": face '" + face + "' does not exist in a 2D case; " +
                          "expected one of: " + join(faces));
    }
    choice(face_node, face_path, faces);
    if (std::find(open.begin(), open.end(), face) != open.end()) {
      fail(face_node, face_path + ": face '" + face + "' is listed twice");
    }
    open.push_back(face);
  }
  return open;
}

// ---------------------------------------------------------------------------------------------

// Notes where each document and its first node start, and builds nothing.
class DocumentCounter : public YAML::EventHandler {
 public:
  YAML::Mark start, node;
  bool has_node = false;
  void OnDocumentStart(const YAML::Mark& mark) override {
    start = node = mark;
    has_node = false;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { first(m); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override { first(m); }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                const std::string&) override {
    first(m);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    first(m);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    first(m);
  }
  void OnMapEnd() override {}

 private:
  void first(const YAML::Mark& m) {
    if (!has_node) node = m, has_node = true;
  }
};

// The line of a second YAML document after the first, or 0 if there is none. yaml-cpp 0.7's
// LoadAll loops without end, allocating, on some malformed input (a lone ',' yields empty
// documents that consume nothing; upstream jbeder/yaml-cpp#1040), so the parser is asked for
// two documents at most, and a "document" that does not start past the first one is no
// second document.
int second_document_line(const std::string& text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentCounter counter;
  if (!parser.HandleNextDocument(counter)) return 0;
  const int first = counter.start.pos;
  if (!parser.HandleNextDocument(counter)) return 0;
  if (counter.start.pos <= first) return 0;
  return (counter.has_node ? counter.node : counter.start).line + 1;
}

bool blank_yaml(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') return false;
  }
  return true;
}

// Parses the YAML text; a case file holds exactly one document.
YAML::Node parse_yaml(const std::string& text, const std::string& file) {
  YAML::Node root;
  int second = 0;
  try {
    root = YAML::Load(text);
    second = second_document_line(text);
  } catch (const YAML::ParserException& e) {
    throw CaseError(file, e.mark.is_null() ? 0 : e.mark.line + 1, "YAML syntax error: " + e.msg);
  }
  if (root.IsNull() && blank_yaml(text)) {
    throw CaseError(file, 1, "the case file is empty; expected at least dim, dp, time and bodies");
  }
  if (second > 0) {
    throw CaseError(file, second,
                    "a second YAML document ('---') was found; a case file holds exactly one");
  }
  return root;
}

std::string default_case_name(const std::string& file_label) {
  return make_safe_name(std::filesystem::path(file_label).stem().string());
}

}  // namespace
}  // namespace case_parse

CaseError::CaseError(const std::string& file, int line, const std::string& message)
    : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                         message),
      file_(file),
      line_(line),
      message_(message) {}

CaseSpec parse_case_text(const std::string& text, const std::string& file_label) {
  const YAML::Node root = case_parse::parse_yaml(text, file_label);
  CaseSpec spec;
  try {
    spec = case_parse::CaseReader(file_label).read(root);
  } catch (const YAML::Exception& e) {
    // The reader avoids throwing yaml-cpp conversions; this only guards against the unforeseen.
    throw CaseError(file_label, e.mark.is_null() ? 0 : e.mark.line + 1, e.msg);
  }
  spec.file = file_label;
  spec.text = text;
  if (spec.name.empty()) spec.name = case_parse::default_case_name(file_label);
  return spec;
}

CaseSpec load_case_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw CaseError(path, 0, "case file not found");
  if (std::filesystem::is_directory(path, ec)) {
    throw CaseError(path, 0, "is a directory, not a case file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError(path, 0, "cannot open the case file for reading");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw CaseError(path, 0, "error while reading the case file");
  return parse_case_text(content.str(), path);
}

namespace {

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Sets root[path...] = value for one `key.path=value` edit.
void apply_case_set(YAML::Node& root, const std::string& set, const std::string& file) {
  const auto fail = [&](const std::string& what) {
    throw CaseError(file, 0, "--set " + set + ": " + what);
  };
  const auto eq = set.find('=');
  if (eq == std::string::npos || eq == 0)
    fail("expected key.path=value (e.g. physics.boundary.model=mdbc)");
  const std::string path = set.substr(0, eq), text = set.substr(eq + 1);
  if (text.find_first_not_of(" \t") == std::string::npos)
    fail("no value after '=' (write a YAML value: mdbc, 0.004, {model: fickian}, [0, -9.81])");
  std::vector<std::string> keys;
  for (std::size_t start = 0;;) {
    const auto dot = path.find('.', start);
    keys.push_back(path.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (keys.back().empty()) fail("an empty key in '" + path + "'");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    fail("the value is not valid YAML: " + e.msg);
  }
  // Walk down, creating missing maps; list items by index.
  std::vector<YAML::Node> chain{root};
  std::string walked;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    YAML::Node parent = chain.back();
    const std::string& k = keys[i];
    const bool last = i + 1 == keys.size();
    if (parent.IsSequence()) {
      if (!all_digits(k) || k.size() > 9)
        fail("'" + walked + "' is a list of " + std::to_string(parent.size()) +
             " items: expected an item index from 0, got '" + k + "'");
      const std::size_t idx = std::stoul(k);
      if (last && idx == parent.size()) {
        parent.push_back(value);  // the index after the last item appends one
      } else if (idx >= parent.size()) {
        fail("'" + walked + "' has " + std::to_string(parent.size()) + " items, no item " + k);
      } else if (last) {
        parent[idx] = value;
      } else {
        chain.push_back(parent[idx]);
      }
    } else if (parent.IsMap() || parent.IsNull() || !parent.IsDefined()) {
      if (last) {
        parent[k] = value;
      } else {
        chain.push_back(parent[k]);
      }
    } else {
      fail("'" + walked + "' holds a value, not a map: it has no key '" + k + "'");
    }
    walked += (walked.empty() ? "" : ".") + k;
  }
}

}  // namespace

std::string edit_case_text(const std::string& text, const std::vector<std::string>& sets,
                           const std::string& file_label) {
  YAML::Node root = case_parse::parse_yaml(text, file_label);
  if (!root.IsMap()) throw CaseError(file_label, 1, "the case file is not a map of keys");
  for (const std::string& set : sets) apply_case_set(root, set, file_label);
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

CaseSpec load_case_file(const std::string& path, const std::vector<std::string>& sets) {
  CaseSpec spec = load_case_file(path);
  if (sets.empty()) return spec;
  return parse_case_text(edit_case_text(spec.text, sets, path), path);
}

}  // namespace swell
