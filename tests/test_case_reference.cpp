// The case-file schema against the reader, the generated reference against docs/, and the run
// header's derived quantities against the solver (case/schema.hpp, run/run.cpp).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "case/model_names.hpp"
#include "case/reader.hpp"
#include "case/schema.hpp"
#include "case/setup.hpp"
#include "run/run.hpp"
#include "waves/spectrum.hpp"

namespace {

namespace fs = std::filesystem;
namespace schema = swell::case_schema;
using swell::CaseError;
using swell::CaseSpec;

// Case texts are labelled inside tests/data, so a motion file resolves to tests/data/.
const std::string kLabel = std::string(SWELL_SOURCE_DIR) + "/tests/data/reference_case.yaml";

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string joined(const schema::Names& names) {
  std::string out;
  for (const auto n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

// --- building cases around one map --------------------------------------------------------------

using Pairs = std::vector<std::pair<std::string, std::string>>;

// "{k: v, ...}" from `pairs`, with `key` (if not empty) replaced by, or added as, `value`.
std::string flow_map(const Pairs& pairs, const std::string& key = "",
                     const std::string& value = "") {
  std::string out;
  for (const auto& [k, v] : pairs)
    if (k != key) out += (out.empty() ? "" : ", ") + k + ": " + v;
  if (!key.empty()) out += (out.empty() ? "" : ", ") + key + ": " + value;
  return "{" + out + "}";
}

const std::string kTank2 = "{name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}}";
const std::string kWater2 =
    "{name: water, kind: fluid, shape: {box: {min: [0.1, 0.1], max: [0.5, 0.5]}}}";
const std::string kTank3 =
    "{name: tank, kind: boundary, shape: {box: {min: [0, 0, 0], max: [1, 1, 1]}}}";
const std::string kWater3 =
    "{name: water, kind: fluid, shape: {box: {min: [0.1, 0.1, 0.1], max: [0.5, 0.5, 0.5]}}}";

// A 2D case (3D with dim 3) whose bodies are `tank` and `water`, plus `extra` top-level lines.
std::string doc(const std::string& extra, int dim = 2, const std::string& tank = "",
                const std::string& water = "", const std::string& time = "{end: 0.001}") {
  return "dim: " + std::to_string(dim) + "\ndp: 0.05\ntime: " + time + "\nbodies:\n  - " +
         (tank.empty() ? (dim == 2 ? kTank2 : kTank3) : tank) + "\n  - " +
         (water.empty() ? (dim == 2 ? kWater2 : kWater3) : water) + "\n" + extra;
}

// One way to write a map of a schema section in a given form: its content (`pairs`), where it
// sits in a case (`wrap` makes the whole case text from the map) and its key path in messages.
struct Base {
  std::string section, form;
  Pairs pairs;
  std::function<std::string(const std::string&)> wrap;
  std::string path;
  bool exclusive = false;  // the map holds one key: an injected key replaces `pairs`
};

// The case text of base `b` with `key: value` added to (or replacing it in) its map.
std::string with_key(const Base& b, const std::string& key, const std::string& value);

std::string tank_with(const std::string& body_key, const std::string& map) {
  return "{name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}, " + body_key +
         ": " + map + "}";
}

std::vector<Base> bases() {
  std::vector<Base> b;
  const auto top = [](const std::string& key) {
    return [key](const std::string& m) { return doc(key + ": " + m + "\n"); };
  };
  b.push_back({"",
               "",
               {{"dim", "2"},
                {"dp", "0.05"},
                {"time", "{end: 0.001}"},
                {"bodies", "[" + kTank2 + ", " + kWater2 + "]"}},
               [](const std::string& m) { return m + "\n"; },
               ""});
  for (const char* s : {"physics", "output", "watchdog", "limits"})
    b.push_back({s, "", {}, top(s), s});
  const auto physics = [](const std::string& key) {
    return [key](const std::string& m) { return doc("physics: {" + key + ": " + m + "}\n"); };
  };
  b.push_back({"physics.viscosity",
               "artificial",
               {{"model", "artificial"}},
               physics("viscosity"),
               "physics.viscosity"});
  b.push_back({"physics.viscosity",
               "laminar",
               {{"model", "laminar"}},
               physics("viscosity"),
               "physics.viscosity"});
  for (const char* m : {"fourtakas", "molteni", "none"})
    b.push_back({"physics.density_diffusion",
                 m,
                 {{"model", m}},
                 physics("density_diffusion"),
                 "physics.density_diffusion"});
  for (const char* m : {"dbc", "mdbc"})
    b.push_back({"physics.boundary", m, {{"model", m}}, physics("boundary"), "physics.boundary"});
  for (const char* m : {"none", "fickian"})
    b.push_back({"physics.shifting", m, {{"model", m}}, physics("shifting"), "physics.shifting"});
  b.push_back({"physics.corrections", "", {}, physics("corrections"), "physics.corrections"});
  b.push_back({"time",
               "",
               {{"end", "0.001"}},
               [](const std::string& m) { return doc("", 2, "", "", m); },
               "time"});
  b.push_back(
      {"time.settling",
       "",
       {{"duration", "1"}},
       [](const std::string& m) { return doc("", 2, "", "", "{end: 0.001, settling: " + m + "}"); },
       "time.settling"});
  b.push_back({"domain", "", {{"min", "[-1, -1]"}, {"max", "[2, 2]"}}, top("domain"), "domain"});

  const Pairs tank = {
      {"name", "tank"}, {"kind", "boundary"}, {"shape", "{box: {min: [0, 0], max: [1, 1]}}"}};
  const Pairs water = {
      {"name", "water"}, {"kind", "fluid"}, {"shape", "{box: {min: [0.1, 0.1], max: [0.5, 0.5]}}"}};
  b.push_back({"bodies[]", "boundary", tank, [](const std::string& m) { return doc("", 2, m); },
               "bodies[0]"});
  b.push_back({"bodies[]", "fluid", water, [](const std::string& m) { return doc("", 2, "", m); },
               "bodies[1]"});
  b.push_back({"bodies[].fill",
               "",
               {{"below", "0.3"}, {"inside", "tank"}},
               [](const std::string& m) {
                 return doc("", 2, "", "{name: water, kind: fluid, fill: " + m + "}");
               },
               "bodies[1].fill"});
  b.push_back({"bodies[].shape",
               "",
               {{"box", "{min: [0, 0], max: [1, 1]}"}},
               [](const std::string& m) {
                 return doc("", 2, "{name: tank, kind: boundary, shape: " + m + "}");
               },
               "bodies[0].shape",
               true});
  const auto shape = [](const std::string& kind, int dim) {
    return [kind, dim](const std::string& m) {
      return doc("", dim, "{name: tank, kind: boundary, shape: {" + kind + ": " + m + "}}");
    };
  };
  b.push_back({"bodies[].shape.box",
               "",
               {{"min", "[0, 0]"}, {"max", "[1, 1]"}},
               shape("box", 2),
               "bodies[0].shape.box"});
  b.push_back({"bodies[].shape.cylinder",
               "2D",
               {{"center", "[0.5, 0.5]"}, {"radius", "0.2"}},
               shape("cylinder", 2),
               "bodies[0].shape.cylinder"});
  b.push_back({"bodies[].shape.cylinder",
               "3D",
               {{"p1", "[0, 0, 0]"}, {"p2", "[0, 0, 1]"}, {"radius", "0.2"}},
               shape("cylinder", 3),
               "bodies[0].shape.cylinder"});
  b.push_back({"bodies[].shape.sphere",
               "",
               {{"center", "[0.5, 0.5]"}, {"radius", "0.2"}},
               shape("sphere", 2),
               "bodies[0].shape.sphere"});
  b.push_back({"bodies[].shape.polygon",
               "",
               {{"points", "[[0, 0], [1, 0], [0, 1]]"}},
               shape("polygon", 2),
               "bodies[0].shape.polygon"});
  b.push_back({"bodies[].shape.mesh",
               "",
               {{"file", "tank.stl"}, {"slice_y", "0"}},
               shape("mesh", 2),
               "bodies[0].shape.mesh"});

  const auto motion = [](const std::string& m) { return doc("", 2, tank_with("motion", m)); };
  const std::string mp = "bodies[0].motion";
  b.push_back(
      {"bodies[].motion", "linear", {{"type", "linear"}, {"velocity", "[0.1, 0]"}}, motion, mp});
  b.push_back({"bodies[].motion",
               "sinusoidal",
               {{"type", "sinusoidal"}, {"amplitude", "0.05"}, {"period", "1"}},
               motion,
               mp});
  b.push_back({"bodies[].motion",
               "rotation",
               {{"type", "rotation"}, {"centre", "[0.5, 0]"}, {"rate", "10"}},
               motion,
               mp});
  b.push_back({"bodies[].motion",
               "rotation",
               {{"type", "rotation"}, {"centre", "[0.5, 0]"}, {"amplitude", "10"}, {"period", "2"}},
               motion,
               mp});
  b.push_back(
      {"bodies[].motion",
       "file",
       {{"type", "file"}, {"file", "motion_flap.csv"}, {"quantity", "angle"}, {"centre", "[0, 0]"}},
       motion,
       mp});
  b.push_back({"bodies[].motion",
               "file",
               {{"type", "file"}, {"file", "motion_flap.csv"}, {"quantity", "displacement"}},
               motion,
               mp});
  const Pairs regular = {{"type", "wave"},
                         {"wave", "regular"},
                         {"depth", "0.5"},
                         {"height", "0.05"},
                         {"period", "1.4"}};
  b.push_back({"bodies[].motion", "wave:regular", regular, motion, mp});
  b.push_back({"bodies[].motion",
               "wave:regular",
               {{"type", "wave"},
                {"paddle", "flap"},
                {"hinge", "[0.2, 0.1]"},
                {"wave", "regular"},
                {"depth", "0.5"},
                {"height", "0.05"},
                {"period", "1.6"}},
               motion,
               mp});
  b.push_back({"bodies[].motion",
               "wave:solitary",
               {{"type", "wave"}, {"wave", "solitary"}, {"depth", "0.4"}, {"height", "0.08"}},
               motion,
               mp});
  b.push_back(
      {"bodies[].motion",
       "wave:irregular",
       {{"type", "wave"}, {"wave", "irregular"}, {"depth", "0.6"}, {"hs", "0.06"}, {"tp", "1.5"}},
       motion,
       mp});
  b.push_back({"bodies[].motion",
               "wave:focused",
               {{"type", "wave"},
                {"wave", "focused"},
                {"depth", "0.6"},
                {"amplitude", "0.06"},
                {"tp", "1.4"},
                {"focus_distance", "6"},
                {"focus_time", "20"}},
               motion,
               mp});
  b.push_back({"bodies[].motion.absorption",
               "",
               {},
               [regular](const std::string& m) {
                 return doc("", 2, tank_with("motion", flow_map(regular, "absorption", m)));
               },
               mp + ".absorption"});

  const auto gauge = [](const std::string& m) { return doc("gauges:\n  - " + m + "\n"); };
  b.push_back({"gauges[]",
               "pressure",
               {{"name", "P"}, {"kind", "pressure"}, {"at", "[0.5, 0.1]"}},
               gauge,
               "gauges[0]"});
  b.push_back({"gauges[]",
               "pressure",
               {{"name", "P"}, {"kind", "pressure"}, {"at", "[0.5, 0.1]"}, {"normal", "[-1, 0]"}},
               gauge,
               "gauges[0]"});
  b.push_back({"gauges[]",
               "height",
               {{"name", "H"}, {"kind", "height"}, {"at", "[0.5, 0]"}},
               gauge,
               "gauges[0]"});
  b.push_back({"gauges[]",
               "velocity",
               {{"name", "V"}, {"kind", "velocity"}, {"at", "[0.5, 0.1]"}},
               gauge,
               "gauges[0]"});
  b.push_back({"gauges[]",
               "force",
               {{"name", "F"}, {"kind", "force"}, {"body", "tank"}},
               gauge,
               "gauges[0]"});
  b.push_back({"gauges[]", "front", {{"name", "X"}, {"kind", "front"}}, gauge, "gauges[0]"});
  b.push_back({"gauges[]",
               "runup",
               {{"name", "R"}, {"kind", "runup"}, {"from", "[0.1, 0]"}, {"to", "[0.9, 0.4]"}},
               gauge,
               "gauges[0]"});

  const auto zone = [](const std::string& m) { return doc("damping:\n  - " + m + "\n"); };
  b.push_back({"damping[]",
               "plane",
               {{"name", "z"}, {"plane", "{at: [0.5, 0], direction: [1, 0]}"}, {"length", "0.5"}},
               zone,
               "damping[0]"});
  b.push_back({"damping[]",
               "box",
               {{"name", "z"}, {"box", "{min: [0, 0], max: [1, 1]}"}, {"direction", "[1, 0]"}},
               zone,
               "damping[0]"});
  b.push_back({"damping[].plane",
               "",
               {{"at", "[0.5, 0]"}, {"direction", "[1, 0]"}},
               [](const std::string& m) {
                 return doc("damping:\n  - {name: z, length: 0.5, plane: " + m + "}\n");
               },
               "damping[0].plane"});
  b.push_back({"damping[].box",
               "",
               {{"min", "[0, 0]"}, {"max", "[1, 1]"}},
               [](const std::string& m) {
                 return doc("damping:\n  - {name: z, direction: [1, 0], box: " + m + "}\n");
               },
               "damping[0].box"});
  return b;
}

std::string with_key(const Base& b, const std::string& key, const std::string& value) {
  return b.wrap(flow_map(b.exclusive ? Pairs{} : b.pairs, key, value));
}

// The message of the CaseError `text` raises, or "" when it parses.
std::string parse_error(const std::string& text) {
  try {
    swell::parse_case_text(text, kLabel);
  } catch (const CaseError& e) {
    return e.message();
  }
  return "";
}

// Whether `message` is about key path `path` (it starts with it, or quotes it).
bool names_path(const std::string& message, const std::string& path) {
  if (path.empty()) return !message.empty();
  for (const char next : {':', '.', '['})
    if (message.rfind(path + next, 0) == 0) return true;
  return message.find("'" + path + "'") != std::string::npos ||
         message.find("'" + path + ".") != std::string::npos;
}

std::string child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

bool base_has_form(const Base& b, const std::string& form) {
  return b.form == form || b.form.rfind(form + ":", 0) == 0;
}

std::vector<std::string> split_forms(std::string_view s) {
  std::vector<std::string> out;
  std::istringstream in{std::string(s)};
  for (std::string f; in >> f;) out.push_back(f);
  return out;
}

// --- the schema against the reader --------------------------------------------------------------

TEST(CaseSchema, EveryBaseCaseParses) {
  for (const Base& b : bases()) {
    const std::string text = b.wrap(flow_map(b.pairs));
    EXPECT_EQ(parse_error(text), "") << b.section << " (" << b.form << "):\n" << text;
  }
}

TEST(CaseSchema, EverySectionHasABaseCase) {
  const auto all = bases();
  for (const auto& s : schema::sections()) {
    const bool found =
        std::any_of(all.begin(), all.end(), [&](const Base& b) { return b.section == s.path; });
    EXPECT_TRUE(found) << "no base case for section '" << s.path << "'";
    for (const std::string& f : split_forms(s.forms)) {
      const bool has = std::any_of(all.begin(), all.end(), [&](const Base& b) {
        return b.section == s.path && base_has_form(b, f);
      });
      EXPECT_TRUE(has) << "no base case for section '" << s.path << "' form " << f;
    }
  }
}

// Every schema key is read by the parser: a value of the wrong type (a map) under it is an
// error naming its path, in every form the schema gives it. A key listed in the schema but
// ignored by the reader parses silently and fails here.
TEST(CaseSchema, EveryKeyIsReadInEveryForm) {
  const auto all = bases();
  int checked = 0;
  for (const schema::Key& k : schema::keys()) {
    const std::string key(k.name);
    std::vector<std::string> wanted = split_forms(k.forms);
    if (wanted.empty()) wanted.push_back("");
    for (const std::string& form : wanted) {
      // At least one base case of the form reports it (a rotation's `amplitude` only where
      // the base gives no `rate`).
      int tried = 0;
      bool read = false;
      std::string messages;
      for (const Base& b : all) {
        if (b.section != k.section || (!form.empty() && !base_has_form(b, form))) continue;
        ++tried;
        const std::string message = parse_error(with_key(b, key, "{zz_bogus: 1}"));
        read = read || names_path(message, child(b.path, key));
        messages += "\n  " + message;
      }
      ++checked;
      EXPECT_GT(tried, 0) << "no base case for " << k.section << "." << key << " (" << form << ")";
      EXPECT_TRUE(read) << "schema key '" << child(std::string(k.section), key) << "' (" << form
                        << "): no error naming it when its value is a map; got:" << messages;
    }
  }
  EXPECT_GT(checked, 150);
}

// The reverse: every map the reader reads refuses a key the schema lacks, and lists the
// schema's keys for that form as the allowed ones.
TEST(CaseSchema, EveryMapRefusesKeysOutsideTheSchema) {
  for (const Base& b : bases()) {
    const std::string text = with_key(b, "zz_bogus", "1");
    const std::string message = parse_error(text);
    EXPECT_NE(message.find("zz_bogus"), std::string::npos) << b.section << ": " << message;
    EXPECT_NE(message.find("unknown"), std::string::npos) << b.section << ": " << message;
    if (b.section == "bodies[].motion.absorption") continue;  // a sentence, not a list
    const schema::Section& s = schema::section(b.section);
    const std::string form = b.form.substr(0, b.form.find(':'));
    const schema::Names expected =
        s.forms.empty() ? schema::all_keys(b.section) : schema::keys_for(b.section, form);
    const std::string list = joined(expected);
    ASSERT_GE(message.size(), list.size()) << message;
    EXPECT_EQ(message.substr(message.size() - list.size()), list)
        << b.section << " (" << b.form << "): " << message;
  }
}

// The reader's own code names no key the schema lacks: every key literal in find(), require(),
// number_pos(), child() and node["..."] of case/*.cpp is a schema key.
TEST(CaseSchema, ReaderSourcesNameOnlySchemaKeys) {
  std::set<std::string> known;
  for (const auto& k : schema::keys()) known.insert(std::string(k.name));
  const std::regex call(R"(\b(?:find|require|number_pos|child)\(([^()]*)\))");
  const std::regex index(R"(\[\"([A-Za-z_0-9]+)\"\])");
  const std::regex last_literal(R"(\"([A-Za-z_0-9]+)\"\s*$)");
  int literals = 0;
  for (const char* file : {"reader.cpp", "gauges.cpp", "motion.cpp", "damping.cpp", "shapes.cpp"}) {
    const std::string src = read_file(fs::path(SWELL_SOURCE_DIR) / "case" / file);
    ASSERT_FALSE(src.empty()) << file;
    std::vector<std::string> names;
    for (auto it = std::sregex_iterator(src.begin(), src.end(), call); it != std::sregex_iterator();
         ++it) {
      const std::string args = (*it)[1];
      std::smatch m;
      if (std::regex_search(args, m, last_literal)) names.push_back(m[1]);
    }
    for (auto it = std::sregex_iterator(src.begin(), src.end(), index);
         it != std::sregex_iterator(); ++it)
      names.push_back((*it)[1]);
    for (const std::string& n : names) {
      ++literals;
      EXPECT_TRUE(known.count(n)) << "io/" << file << " reads key '" << n
                                  << "', which the schema (case/schema.cpp) lacks";
    }
  }
  EXPECT_GT(literals, 100);
}

// Schema defaults that are numbers or names equal what the reader leaves without the key.
TEST(CaseSchema, DefaultsAreTheReadersDefaults) {
  const CaseSpec plain = swell::parse_case_text(doc(""), kLabel);
  const CaseSpec tuned = swell::parse_case_text(
      doc("physics: {boundary: {model: mdbc}, shifting: {model: fickian}}\n"
          "damping:\n  - {name: z, plane: {at: [0.5, 0], direction: [1, 0]}, length: 0.5}\n",
          2, tank_with("motion", "{type: linear, velocity: [0.1, 0]}"), "",
          "{end: 0.001, settling: {duration: 1}}"),
      kLabel);
  const CaseSpec laminar =
      swell::parse_case_text(doc("physics: {viscosity: {model: laminar}}\n"), kLabel);
  const CaseSpec wave = swell::parse_case_text(
      doc("", 2,
          tank_with("motion",
                    "{type: wave, wave: regular, depth: 0.5, height: 0.05, period: 1.4}")),
      kLabel);
  const CaseSpec sine = swell::parse_case_text(
      doc("", 2, tank_with("motion", "{type: sinusoidal, amplitude: 0.05, period: 1}")), kLabel);
  const swell::waves::SpectrumSpec spectrum;
  const std::map<std::string, double> numbers = {
      {"physics.rho0", plain.rho0},
      {"physics.coefsound", plain.coefsound},
      {"physics.coefh", plain.coefh},
      {"physics.viscosity.alpha", plain.alpha},
      {"physics.viscosity.nu", laminar.nu},
      {"physics.density_diffusion.delta", plain.delta},
      {"physics.boundary.det_min", tuned.mdbc_det_min},
      {"physics.shifting.coefficient", tuned.shift_coefficient},
      {"physics.corrections.det_min", plain.kgc_det_min},
      {"physics.corrections.shepard_reinit", plain.shepard_reinit},
      {"time.cfl", plain.cfl},
      {"time.verlet_steps", plain.verlet_steps},
      {"time.settling.rate", tuned.settling->rate},
      {"watchdog.every", plain.watchdog.every},
      {"watchdog.warn_excluded", plain.watchdog.warn_excluded_fraction},
      {"watchdog.max_excluded", plain.watchdog.max_excluded_fraction},
      {"watchdog.max_density", plain.watchdog.max_density_factor},
      {"watchdog.penetration_depth", plain.watchdog.penetration_depth},
      {"watchdog.max_penetrated", plain.watchdog.max_penetrated_fraction},
      {"watchdog.dt_collapse", plain.dt_collapse},
      {"limits.max_particles", plain.max_particles},
      {"bodies[].layers", plain.bodies[0].layers},
      {"bodies[].motion.start", tuned.bodies[0].motion.start},
      {"bodies[].motion.phase", sine.bodies[0].motion.phase},
      {"bodies[].motion.bed", wave.bodies[0].motion.bed},
      {"bodies[].motion.order", wave.bodies[0].motion.wave_order},
      {"bodies[].motion.gamma", spectrum.gamma},
      {"bodies[].motion.seed", static_cast<double>(spectrum.seed)},
      {"bodies[].shape.mesh.scale", 1.0},  // Placement::scale is Ones (checked below)
      {"damping[].rate", tuned.damping[0].zone.rate},
      {"damping[].start", tuned.damping[0].zone.start},
  };
  const std::map<std::string, std::string> texts = {
      {"physics.kernel", swell::kernel_name(plain.kernel)},
      {"physics.viscosity.model", swell::viscosity_name(plain.viscosity_model)},
      {"physics.density_diffusion.model", swell::diffusion_name(plain.diffusion_model)},
      {"physics.boundary.model", swell::boundary_name(plain.boundary)},
      {"physics.boundary.slip", swell::mdbc_slip_name(tuned.mdbc_slip)},
      {"physics.shifting.model", swell::shifting_name(plain.shifting)},
      {"physics.corrections.kernel_gradient", plain.kernel_gradient_correction ? "kgc" : "none"},
      {"time.integrator", swell::integrator_name(plain.integrator)},
      {"bodies[].walls",
       plain.bodies[0].walls == swell::BodySpec::Walls::Inside ? "inside" : "outside"},
      {"bodies[].motion.paddle", "piston"},  // the default PaddleGeometry (checked by test_motion)
      {"output.vtk", plain.vtk ? "true" : "false"},
      {"output.vtk_split", plain.vtk_split ? "true" : "false"},
      {"output.hdf5", plain.hdf5 ? "true" : "false"},
      {"damping[].ramp",
       tuned.damping[0].zone.ramp == swell::DampingRamp::Quadratic ? "quadratic" : "cosine"},
  };
  EXPECT_EQ(swell::Placement{}.scale, Eigen::Vector3d::Ones());
  // Every default that reads as a plain number is checked: a new one needs a line above.
  std::set<std::string> seen;
  for (const schema::Key& k : schema::keys()) {
    const std::string path = child(std::string(k.section), std::string(k.name));
    const std::string def(k.default_value);
    char* end = nullptr;
    const double v = std::strtod(def.c_str(), &end);
    const bool is_number = !def.empty() && *end == '\0' && def.find_first_of("0123456789") == 0;
    if (is_number) {
      if (!seen.insert(path).second && !numbers.count(path)) continue;
      ASSERT_TRUE(numbers.count(path)) << "numeric default of " << path << " is not checked";
      EXPECT_DOUBLE_EQ(numbers.at(path), v) << path << " (" << k.forms << ")";
    } else if (texts.count(path)) {
      EXPECT_EQ(def, texts.at(path)) << path;
    }
  }
  for (const auto& [path, value] : texts) {
    const auto it =
        std::find_if(schema::keys().begin(), schema::keys().end(), [&](const schema::Key& k) {
          return child(std::string(k.section), std::string(k.name)) == path;
        });
    ASSERT_NE(it, schema::keys().end()) << path;
  }
}

TEST(CaseSchema, ChoiceKeysListTheReadersValues) {
  // A choice key given an unknown value is refused with the list the reader accepts.
  struct Case {
    std::string section, key, form;
  };
  const auto all = bases();
  for (const schema::Key& k : schema::keys()) {
    if (k.type != "choice") continue;
    for (const Base& b : all) {
      if (b.section != k.section ||
          (!k.forms.empty() && !base_has_form(b, split_forms(k.forms)[0])))
        continue;
      const std::string message = parse_error(with_key(b, std::string(k.name), "zz_bogus"));
      ASSERT_TRUE(names_path(message, child(b.path, std::string(k.name)))) << message;
      const std::size_t at = message.find("expected one of: ");
      if (at == std::string::npos) break;  // a described choice (gauge level, sampling)
      std::string list = message.substr(at + 17);
      std::string want;
      for (const auto c : schema::choices(k.section, k.name))
        want += (want.empty() ? "" : ", ") + std::string(c);
      EXPECT_EQ(list, want) << k.section << "." << k.name;
      break;
    }
  }
}

// Numeric ranges written as "> a", ">= a", "[a, b]", "(a, b]", ... are the reader's: values just
// outside a bound are errors naming the key, a closed bound itself and values just inside it
// parse.
TEST(CaseSchema, NumericRangesAreTheReadersRanges) {
  const std::regex bound(R"(^(>|>=) (-?[0-9.e+-]+)$)");
  const std::regex interval(R"(^([\[(])(-?[0-9.e+-]+), (-?[0-9.e+-]+)([\])])$)");
  const auto all = bases();
  int checked = 0;
  for (const schema::Key& k : schema::keys()) {
    if (k.type != "number" && k.type != "integer") continue;
    const bool integer = k.type == "integer";
    std::string range(k.allowed);
    range = range.substr(0, range.find(" ("));  // ">= 0 (0: off)" -> ">= 0"
    range = range.substr(0, range.find(';'));
    std::vector<double> refuse, accept;
    // One side of the range: the bound, whether it is closed, and the side the values lie on.
    const auto side = [&](double a, bool closed, double sign) {
      const double eps = integer ? 1.0 : 1e-6 * std::max(1.0, std::abs(a));
      if (closed) {
        refuse.push_back(a - sign * eps);
        accept.push_back(a);
      } else {
        refuse.push_back(a);
        accept.push_back(a + sign * eps);
      }
    };
    std::smatch m;
    if (std::regex_match(range, m, bound)) {
      side(std::stod(m[2]), m[1] == ">=", 1.0);
    } else if (std::regex_match(range, m, interval)) {
      side(std::stod(m[2]), m[1] == "[", 1.0);
      side(std::stod(m[3]), m[4] == "]", -1.0);
    } else {
      continue;
    }
    const std::vector<std::string> forms = split_forms(k.forms);
    const std::string form = forms.empty() ? "" : forms[0];
    const std::string key(k.name);
    const auto text = [](double v) {
      std::ostringstream o;
      o << std::setprecision(17) << v;
      return o.str();
    };
    bool agrees = false;
    std::string why;
    for (const Base& b : all) {
      if (b.section != k.section || (!form.empty() && !base_has_form(b, form))) continue;
      bool ok = true;
      for (const double v : refuse) {
        const std::string message = parse_error(with_key(b, key, text(v)));
        if (!names_path(message, child(b.path, key)))
          ok = false, why += "\n  " + text(v) + " taken: '" + message + "'";
      }
      for (const double v : accept) {
        const std::string message = parse_error(with_key(b, key, text(v)));
        if (!message.empty()) ok = false, why += "\n  " + text(v) + " refused: " + message;
      }
      if (ok) {
        agrees = true;
        break;
      }
    }
    EXPECT_TRUE(agrees) << k.section << "." << key << " (" << k.forms << "): schema range '"
                        << k.allowed << "' is not the reader's:" << why;
    ++checked;
  }
  EXPECT_GT(checked, 40);
}

// --- the generated reference
// -----------------------------------------------------------------------

TEST(CaseReference, CommittedDocumentIsCurrent) {
  const fs::path doc_path = fs::path(SWELL_SOURCE_DIR) / "docs" / "case_reference.md";
  const std::string committed = read_file(doc_path);
  if (committed != schema::reference_markdown())
    FAIL() << "docs/case_reference.md is stale: run `swell help case > docs/case_reference.md`";
}

TEST(CaseReference, CoversEveryKeyAndTheNotes) {
  const std::string md = schema::reference_markdown();
  for (const schema::Key& k : schema::keys()) {
    const std::string path = child(std::string(k.section), std::string(k.name));
    EXPECT_NE(md.find("| `" + path + "` |"), std::string::npos) << path;
  }
  for (const char* note : {"### `domain`: particles that leave it are deleted", "### `layers`",
                           "### Where the `front` gauge looks", "### What `walls: outside` builds",
                           "`h = coefh sqrt(dim) dp`", "`B = c0^2 rho0 / gamma`"})
    EXPECT_NE(md.find(note), std::string::npos) << note;
}

TEST(CaseReference, OneEntryByItsPath) {
  const auto coefh = schema::reference_entry("physics.coefh");
  ASSERT_TRUE(coefh);
  EXPECT_NE(coefh->find("| `physics.coefh` |"), std::string::npos);
  EXPECT_NE(coefh->find("[0.5, 4]"), std::string::npos);
  // List indices are optional; a key shared by forms gives one row per form.
  const auto at = schema::reference_entry("gauges[2].at");
  ASSERT_TRUE(at);
  EXPECT_NE(at->find("kind: pressure"), std::string::npos);
  EXPECT_NE(at->find("kind: height"), std::string::npos);
  EXPECT_EQ(schema::reference_entry("bodies.motion.height"),
            schema::reference_entry("bodies[].motion.height"));
  const auto section = schema::reference_entry("physics.boundary");
  ASSERT_TRUE(section);
  EXPECT_NE(section->find("`physics.boundary.det_min`"), std::string::npos);
  EXPECT_FALSE(schema::reference_entry("physics.nosuch"));
}

// `swell help case` prints the same text; an unknown path is an input error (exit 2).
TEST(CaseReference, HelpCommand) {
  const std::string swell = std::string(SWELL_BINARY_DIR) + "/swell";
  const auto run = [&](const std::string& args, int& rc) {
    std::string out;
    FILE* p = popen((swell + " " + args + " 2>&1").c_str(), "r");
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    const int status = pclose(p);
    rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return out;
  };
  int rc = -1;
  EXPECT_EQ(run("help case", rc), schema::reference_markdown());
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(run("help case gauges.band", rc), *schema::reference_entry("gauges.band"));
  EXPECT_EQ(rc, 0);
  const std::string bad = run("help case physics.nosuch", rc);
  EXPECT_EQ(rc, 2);
  EXPECT_NE(bad.find("no key or section 'physics.nosuch'"), std::string::npos) << bad;
}

// --- the run header
// --------------------------------------------------------------------------------

// The number after the last " = " of the header line starting with `start`.
double header_value(const std::string& log, const std::string& start) {
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(start, 0) != 0) continue;
    const std::size_t eq = line.rfind(" = ");
    return std::strtod(line.c_str() + eq + 3, nullptr);
  }
  ADD_FAILURE() << "no header line starting with '" << start << "' in\n" << log;
  return std::nan("");
}

std::string header_line(const std::string& log, const std::string& start) {
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(start, 0) == 0) return line;
  return "";
}

std::string run_log(const std::string& text, const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("swell_reference_" + name);
  fs::remove_all(dir);
  const CaseSpec spec = swell::parse_case_text(text, name + ".yaml");
  swell::RunOptions opt;
  opt.out_dir = dir.string();
  opt.progress = false;
  opt.threads = 1;
  std::ostringstream log;
  opt.log = &log;
  swell::run_case(spec, opt);
  fs::remove_all(dir);
  return log.str();
}

TEST(RunHeader, DerivedQuantitiesAreTheSolversAndTheirFormulas) {
  // A 2D tank with water 0.4 m deep on a 0.02 m lattice; every input away from its default.
  const double dp = 0.02, coefh = 1.2, coefsound = 15.0, rho0 = 1025.0, g = 9.7, cfl = 0.25;
  const double depth = 0.4;
  std::ostringstream t;
  t << "dim: 2\ndp: " << dp << "\nphysics: {rho0: " << rho0 << ", gravity: [0, " << -g
    << "], coefsound: " << coefsound << ", coefh: " << coefh
    << ", kernel: quintic}\ntime: {end: 0.002, cfl: " << cfl << "}\n"
    << "bodies:\n"
       "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.6, 0.6]}}, layers: 3}\n"
       "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.3, "
    << depth << "]}}}\noutput: {every: 0.002, vtk: false, hdf5: false}\n";
  const CaseSpec spec = swell::parse_case_text(t.str(), "header2d.yaml");
  const swell::CaseSetup<2> setup = swell::setup_case<2>(spec);
  const swell::SolverParams& p = setup.params;
  const std::string log = run_log(t.str(), "header2d");

  // The printed values are the solver's parameters.
  const double rel = 1e-9;
  EXPECT_NEAR(header_value(log, "    h = "), p.h, rel * p.h);
  EXPECT_NEAR(header_value(log, "    c0 = "), p.c0, rel * p.c0);
  EXPECT_NEAR(header_value(log, "    B = "), p.tait_b(), rel * p.tait_b());
  EXPECT_NEAR(header_value(log, "    mass = "), setup.particles.mass[0],
              rel * setup.particles.mass[0]);
  EXPECT_NEAR(header_value(log, "    hswl = "), setup.hswl, rel * setup.hswl);
  EXPECT_NEAR(header_value(log, "    support = "), 3.0 * p.h, rel * p.h);

  // ... and they follow the printed formulas, computed here from the case's inputs.
  const double h = coefh * std::sqrt(2.0) * dp;
  const double c0 = coefsound * std::sqrt(g * depth);  // hswl: 20 rows of dp, top - bottom + dp
  EXPECT_NEAR(p.h, h, 1e-12);
  EXPECT_NEAR(setup.hswl, depth, 1e-12);
  EXPECT_NEAR(p.c0, c0, 1e-9 * c0);
  EXPECT_NEAR(p.tait_b(), c0 * c0 * rho0 / 7.0, 1e-9 * p.tait_b());
  EXPECT_NEAR(setup.particles.mass[0], rho0 * dp * dp, 1e-15);
  EXPECT_NE(header_line(log, "    h = ").find("coefh * sqrt(dim) * dp"), std::string::npos);
  EXPECT_NE(header_line(log, "    c0 = ").find("coefsound * sqrt(|g| * hswl)"), std::string::npos);
  EXPECT_NE(header_line(log, "    B = ").find("c0^2 * rho0 / gamma"), std::string::npos);
  EXPECT_NE(header_line(log, "    mass = ").find("rho0 * dp^dim"), std::string::npos);
  EXPECT_NEAR(header_value(log, "    dt at rest: "), cfl * std::sqrt(h / g), 1e-9);
  const std::string rest = header_line(log, "    dt at rest: ");
  EXPECT_NE(rest.find("cfl * h / c0 = "), std::string::npos) << rest;
  // The wall layers the quintic kernel's 3h support needs: ceil(3 * 1.2 * sqrt(2) - 0.5) = 5,
  // and the tank's 3 are named as too few.
  const std::string layers = header_line(log, "    wall layers");
  EXPECT_NE(layers.find("= 5 (fewer: tank 3)"), std::string::npos) << layers;

  // The first step's dt respects the acoustic bound the header prints: dt <= cfl h / c0 (the
  // largest sound speed is at least c0, the walls never drop below rho0).
  swell::CaseSetup<2> s2 = swell::setup_case<2>(spec);
  swell::Simulation<2> sim = swell::make_simulation<2>(s2, std::move(s2.particles));
  sim.step();
  EXPECT_GT(sim.dt(), 0.0);
  EXPECT_LE(sim.dt(), cfl * h / c0 * (1.0 + 1e-12));
}

TEST(RunHeader, LaminarViscosityAddsTheViscousLimitAndGivenHswl) {
  const std::string text =
      "dim: 2\ndp: 0.02\nphysics: {hswl: 0.5, viscosity: {model: laminar, nu: 1.0e-3}}\n"
      "time: {end: 0.001}\nbodies:\n"
      "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.6, 0.6]}}}\n"
      "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.3, 0.2]}}}\n"
      "output: {every: 0.001, vtk: false, hdf5: false}\n";
  const std::string log = run_log(text, "header_laminar");
  const double h = std::sqrt(2.0) * 0.02;
  EXPECT_NEAR(header_value(log, "    hswl = "), 0.5, 1e-12);
  EXPECT_NE(header_line(log, "    hswl = ").find("physics.hswl"), std::string::npos);
  EXPECT_NEAR(header_value(log, "    c0 = "), 20.0 * std::sqrt(9.81 * 0.5), 1e-9);
  const std::string dt = header_line(log, "    dt = ");
  EXPECT_NE(dt.find("min(dt_f, dt_cv, dt_nu)"), std::string::npos) << dt;
  EXPECT_NEAR(header_value(log, "    dt = "), 0.125 * h * h / 1e-3, 1e-12);
  const std::string layers = header_line(log, "    wall layers");
  EXPECT_NE(layers.find("= 3"), std::string::npos) << layers;
  EXPECT_EQ(layers.find("fewer"), std::string::npos) << layers;
}

// A wavemaker run names the two settings that were measured to damp a wave
// (docs/user-guide/waves.md#settings-for-wave-runs): a short smoothing length (coefh < 1.2) and
// artificial viscosity (alpha > 0.001, with the kinematic viscosity it amounts to); the settings
// recommended there silence both.
TEST(RunHeader, WavemakerWarnsOfSettingsThatDampTheWave) {
  const auto text = [](const std::string& physics) {
    return "dim: 2\ndp: 0.02\nphysics: {" + physics +
           "}\ntime: {end: 0.001}\nbodies:\n"
           "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1.2, 0.4]}}, "
           "layers: 4, open: [ymax]}\n"
           "  - {name: paddle, kind: boundary, shape: {box: {min: [0.02, 0], max: [0.1, 0.35]}},"
           " walls: outside, layers: 4, motion: {type: wave, wave: regular, depth: 0.2, height: "
           "0.02, period: 1.0}}\n"
           "  - {name: water, kind: fluid, shape: {box: {min: [0.12, 0], max: [1.2, 0.2]}}}\n"
           "output: {every: 0.001, vtk: false, hdf5: false}\n";
  };
  const std::string defaults = run_log(text("coefsound: 10"), "wave_defaults");
  const std::string hline = header_line(defaults, "  warning: wavemaker paddle: coefh 1 < 1.2");
  EXPECT_NE(hline.find("physics.coefh: 1.5"), std::string::npos) << defaults;
  const std::string vline =
      header_line(defaults, "  warning: wavemaker paddle: artificial viscosity alpha 0.01");
  // nu = alpha h c0 / 8 in 2D: h = sqrt(2) 0.02, c0 = 10 sqrt(9.81 * 0.2).
  const double nu = 0.01 * std::sqrt(2.0) * 0.02 * 10 * std::sqrt(9.81 * 0.2) / 8;
  const auto at = vline.find("/ 8 = ");
  ASSERT_NE(at, std::string::npos) << defaults;
  EXPECT_NEAR(std::stod(vline.substr(at + 6)), nu, 1e-4 * nu) << vline;
  EXPECT_NE(vline.find("{model: laminar, nu: 1.0e-6}"), std::string::npos) << vline;

  const std::string artificial = run_log(text("coefsound: 10, coefh: 1.5"), "wave_artificial");
  EXPECT_EQ(artificial.find("coefh 1.5 < 1.2"), std::string::npos) << artificial;
  EXPECT_NE(artificial.find("artificial viscosity alpha 0.01 damps"), std::string::npos);
  const std::string small =
      run_log(text("coefsound: 10, coefh: 1.5, viscosity: {model: artificial, alpha: 0.001}"),
              "wave_small_alpha");
  EXPECT_EQ(small.find("artificial viscosity alpha"), std::string::npos) << small;
  const std::string recommended =
      run_log(text("coefsound: 10, coefh: 1.5, viscosity: {model: laminar, nu: 1.0e-6}"),
              "wave_recommended");
  EXPECT_NE(recommended.find("wavemaker paddle: regular wave"), std::string::npos) << recommended;
  EXPECT_EQ(recommended.find("< 1.2"), std::string::npos) << recommended;
  EXPECT_EQ(recommended.find("artificial viscosity"), std::string::npos) << recommended;
}

}  // namespace
