#include "validation/validation_manifest.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "case/reader.hpp"
#include "io/resources.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

// Reads one manifest, reporting problems as "<file>:<line>: <key path>: <message>".
class ManifestReader {
 public:
  explicit ManifestReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& path,
                         const std::string& message) const {
    std::string where = file_;
    if (at.IsDefined() && at.Mark().line >= 0) where += ":" + std::to_string(at.Mark().line + 1);
    throw ManifestError(where + ": " + (path.empty() ? "" : path + ": ") + message);
  }

  void check_keys(const YAML::Node& map, const std::string& path,
                  const std::set<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, path, "expected a map");
    for (const auto& kv : map) {
      const std::string key = kv.first.as<std::string>();
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(kv.first, path.empty() ? key : path + "." + key,
             "unknown key (expected one of: " + list + ")");
      }
    }
  }

  YAML::Node require(const YAML::Node& map, const std::string& path, const std::string& key) const {
    const YAML::Node n = map[key];
    if (!n.IsDefined() || n.IsNull()) fail(map, join(path, key), "missing (required)");
    return n;
  }

  std::string text(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar()) fail(n, path, "expected a string");
    return n.as<std::string>();
  }

  double number(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar()) fail(n, path, "expected a number");
    try {
      return n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, path, "expected a number, got '" + n.as<std::string>() + "'");
    }
  }

  Window window(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence() || n.size() != 2) fail(n, path, "expected [t0, t1]");
    Window w{number(n[0], path + "[0]"), number(n[1], path + "[1]")};
    if (!(w.t1 > w.t0)) fail(n, path, "expected t1 > t0");
    return w;
  }

  std::vector<double> positive_list(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence()) fail(n, path, "expected a list of numbers > 0");
    std::vector<double> out;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const double v = number(n[i], path + "[" + std::to_string(i) + "]");
      if (!(v > 0.0)) fail(n[i], path + "[" + std::to_string(i) + "]", "expected a number > 0");
      out.push_back(v);
    }
    return out;
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

std::string resolve(const std::string& dir, const std::string& relative) {
  const fs::path p(relative);
  return (p.is_absolute() ? p : fs::path(dir) / p).lexically_normal().string();
}

std::string format_g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

const ManifestReference* Manifest::reference(const std::string& ref_name) const {
  for (const auto& r : references)
    if (r.name == ref_name) return &r;
  return nullptr;
}

std::string sph_label(double dp) {
  return "sph_dp" + format_g(dp);
}
std::string foam_label(double cell_size) {
  return "foam_dx" + format_g(cell_size);
}

Manifest load_manifest(const std::string& path) {
  ManifestReader rd(path);
  YAML::Node root;
  try {
    std::ifstream in(path);
    if (!in) throw ManifestError(path + ": cannot read the manifest");
    root = YAML::Load(in);
  } catch (const YAML::ParserException& e) {
    throw ManifestError(path + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax: " + e.msg);
  }
  if (!root.IsMap()) throw ManifestError(path + ": expected a map of manifest keys");
  rd.check_keys(root, "",
                {"title", "case", "extra_gauges", "end_time", "normalisation", "references",
                 "gauges", "targets", "runs", "results", "notes"});

  Manifest m;
  m.file = path;
  m.dir = fs::path(path).parent_path().string();
  if (m.dir.empty()) m.dir = ".";
  m.name = fs::path(path).parent_path().filename().string();
  m.title = root["title"] ? rd.text(root["title"], "title") : m.name;
  m.case_file = resolve(m.dir, rd.text(rd.require(root, "", "case"), "case"));
  if (!fs::exists(m.case_file))
    rd.fail(root["case"], "case", "the case file " + m.case_file + " does not exist");
  if (root["extra_gauges"]) {
    if (!root["extra_gauges"].IsSequence())
      rd.fail(root["extra_gauges"], "extra_gauges", "expected a list of gauges (case-file syntax)");
    YAML::Emitter e;
    e << root["extra_gauges"];
    m.extra_gauges_yaml = e.c_str();
  }
  if (root["end_time"]) m.end_time = rd.number(root["end_time"], "end_time");
  if (root["notes"]) m.notes = rd.text(root["notes"], "notes");

  const YAML::Node norm = rd.require(root, "", "normalisation");
  if (!norm.IsMap()) rd.fail(norm, "normalisation", "expected a map name -> {time_scale, ...}");
  for (const auto& kv : norm) {
    const std::string key = kv.first.as<std::string>(), p = "normalisation." + key;
    rd.check_keys(kv.second, p, {"time_scale", "value_scale", "time_label", "value_label"});
    Normalisation n;
    n.name = key;
    n.time_scale = rd.number(rd.require(kv.second, p, "time_scale"), p + ".time_scale");
    n.value_scale = rd.number(rd.require(kv.second, p, "value_scale"), p + ".value_scale");
    if (!(n.time_scale > 0.0)) rd.fail(kv.second["time_scale"], p + ".time_scale", "expected > 0");
    if (!(n.value_scale > 0.0))
      rd.fail(kv.second["value_scale"], p + ".value_scale", "expected > 0");
    if (kv.second["time_label"]) n.time_label = rd.text(kv.second["time_label"], p);
    if (kv.second["value_label"]) n.value_label = rd.text(kv.second["value_label"], p);
    m.normalisations[key] = n;
  }

  const YAML::Node refs = rd.require(root, "", "references");
  if (!refs.IsSequence()) rd.fail(refs, "references", "expected a list of {name, file, label}");
  for (std::size_t i = 0; i < refs.size(); ++i) {
    const std::string p = "references[" + std::to_string(i) + "]";
    rd.check_keys(refs[i], p, {"name", "file", "label", "theory"});
    ManifestReference r;
    r.name = rd.text(rd.require(refs[i], p, "name"), p + ".name");
    if (r.name == "openfoam")
      rd.fail(refs[i]["name"], p + ".name", "'openfoam' is reserved for the OpenFOAM runs");
    if (refs[i]["theory"]) {
      r.theory = rd.text(refs[i]["theory"], p + ".theory");
      if (r.theory != "paddle")
        rd.fail(refs[i]["theory"], p + ".theory",
                "expected 'paddle' (the case's wave-paddle theory), got '" + r.theory + "'");
      if (refs[i]["file"]) rd.fail(refs[i]["file"], p + ".file", "a theory reference has no file");
    } else {
      r.file = resolve(m.dir, rd.text(rd.require(refs[i], p, "file"), p + ".file"));
      if (!fs::exists(r.file))
        rd.fail(refs[i]["file"], p + ".file", "the reference file " + r.file + " does not exist");
    }
    r.label = refs[i]["label"] ? rd.text(refs[i]["label"], p + ".label") : r.name;
    if (m.reference(r.name)) rd.fail(refs[i], p + ".name", "'" + r.name + "' given twice");
    m.references.push_back(r);
  }

  const YAML::Node gauges = rd.require(root, "", "gauges");
  if (!gauges.IsSequence()) rd.fail(gauges, "gauges", "expected a list of gauge comparisons");
  for (std::size_t i = 0; i < gauges.size(); ++i) {
    const std::string p = "gauges[" + std::to_string(i) + "]";
    const YAML::Node g = gauges[i];
    rd.check_keys(
        g, p,
        {"gauge", "normalisation", "reference", "window", "peak_window", "arrival_threshold",
         "relative", "min_reference", "impulse_window", "mean_window", "filter", "harmonic"});
    ManifestGauge mg;
    mg.gauge = rd.text(rd.require(g, p, "gauge"), p + ".gauge");
    mg.normalisation = rd.text(rd.require(g, p, "normalisation"), p + ".normalisation");
    if (!m.normalisations.count(mg.normalisation))
      rd.fail(g["normalisation"], p + ".normalisation",
              "'" + mg.normalisation + "' is not defined under normalisation");
    if (g["reference"]) {
      const YAML::Node cols = g["reference"];
      if (!cols.IsMap())
        rd.fail(cols, p + ".reference", "expected a map reference name -> column name");
      for (const auto& kv : cols) {
        const std::string ref = kv.first.as<std::string>();
        if (!m.reference(ref))
          rd.fail(kv.first, p + ".reference." + ref, "no reference named '" + ref + "'");
        mg.columns[ref] = rd.text(kv.second, p + ".reference." + ref);
      }
    }
    if (g["window"]) mg.request.window = rd.window(g["window"], p + ".window");
    if (g["peak_window"]) {
      mg.request.peak = true;
      mg.request.peak_window = rd.window(g["peak_window"], p + ".peak_window");
    }
    if (g["arrival_threshold"]) {
      mg.request.arrival = true;
      mg.request.arrival_threshold = rd.number(g["arrival_threshold"], p + ".arrival_threshold");
    }
    if (g["relative"]) {
      if (!g["relative"].IsScalar()) rd.fail(g["relative"], p + ".relative", "expected a bool");
      mg.request.relative = g["relative"].as<bool>();
    }
    if (g["min_reference"])
      mg.request.min_reference = rd.number(g["min_reference"], p + ".min_reference");
    if (g["impulse_window"]) {
      mg.request.impulse = true;
      mg.request.impulse_window = rd.window(g["impulse_window"], p + ".impulse_window");
    }
    if (g["mean_window"]) {
      mg.request.mean = true;
      mg.request.mean_window = rd.window(g["mean_window"], p + ".mean_window");
    }
    if (g["filter"]) {
      mg.request.filter = rd.number(g["filter"], p + ".filter");
      if (!(mg.request.filter > 0.0))
        rd.fail(g["filter"], p + ".filter", "expected a width > 0 (normalised time)");
      if (!g["peak_window"])
        rd.fail(g["filter"], p + ".filter", "needs peak_window (the filtered peak is found there)");
    }
    if (g["harmonic"]) {
      const YAML::Node h = g["harmonic"];
      const std::string hp = p + ".harmonic";
      if (!h.IsMap()) rd.fail(h, hp, "expected {period: T, window: [t0, t1]}");
      rd.check_keys(h, hp, {"period", "window"});
      mg.request.harmonic_period = rd.number(rd.require(h, hp, "period"), hp + ".period");
      if (!(mg.request.harmonic_period > 0.0))
        rd.fail(h["period"], hp + ".period", "expected a period > 0 (normalised time)");
      mg.request.harmonic_window =
          h["window"] ? rd.window(h["window"], hp + ".window") : mg.request.window;
    }
    m.gauges.push_back(mg);
  }

  if (root["targets"]) {
    const YAML::Node targets = root["targets"];
    if (!targets.IsSequence()) rd.fail(targets, "targets", "expected a list of targets");
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const std::string p = "targets[" + std::to_string(i) + "]";
      const YAML::Node t = targets[i];
      rd.check_keys(t, p,
                    {"gauge", "against", "metric", "runs", "max", "max_abs", "min", "text",
                     "known_failures"});
      ManifestTarget mt;
      mt.gauge = rd.text(rd.require(t, p, "gauge"), p + ".gauge");
      mt.against = rd.text(rd.require(t, p, "against"), p + ".against");
      if (mt.against != "openfoam" && !m.reference(mt.against))
        rd.fail(t["against"], p + ".against",
                "'" + mt.against + "' is neither a reference nor 'openfoam'");
      mt.metric = rd.text(rd.require(t, p, "metric"), p + ".metric");
      std::string base = mt.metric;
      if (base.size() > 2 && base.substr(base.size() - 2) == "_s")
        base = base.substr(0, base.size() - 2);  // peak_time_error_s: the same in seconds
      bool known = false;
      for (const auto& n : metric_names()) known = known || n == base;
      if (!known) rd.fail(t["metric"], p + ".metric", "unknown metric '" + mt.metric + "'");
      if (t["runs"]) {
        mt.runs = rd.text(t["runs"], p + ".runs");
        if (mt.runs != "sph" && mt.runs != "openfoam" && mt.runs != "all")
          rd.fail(t["runs"], p + ".runs", "expected sph, openfoam or all");
      }
      if (t["max"]) mt.max = rd.number(t["max"], p + ".max");
      if (t["max_abs"]) mt.max_abs = rd.number(t["max_abs"], p + ".max_abs");
      if (t["min"]) mt.min = rd.number(t["min"], p + ".min");
      if (!mt.max && !mt.max_abs && !mt.min)
        rd.fail(t, p, "give at least one bound: max, max_abs or min");
      mt.text = t["text"] ? rd.text(t["text"], p + ".text") : "";
      if (const YAML::Node k = t["known_failures"]) {
        if (!k.IsSequence())
          rd.fail(k, p + ".known_failures", "expected a list of results such as [sph_dp0.005]");
        for (std::size_t j = 0; j < k.size(); ++j)
          mt.known_failures.push_back(
              rd.text(k[j], p + ".known_failures[" + std::to_string(j) + "]"));
      }
      bool gauge_known = false;
      for (const auto& g : m.gauges) gauge_known = gauge_known || g.gauge == mt.gauge;
      if (!gauge_known)
        rd.fail(t["gauge"], p + ".gauge", "'" + mt.gauge + "' is not listed under gauges");
      m.targets.push_back(mt);
    }
  }

  if (root["runs"]) {
    const YAML::Node runs = root["runs"];
    rd.check_keys(runs, "runs", {"sph", "openfoam"});
    if (runs["sph"]) {
      rd.check_keys(runs["sph"], "runs.sph", {"resolutions"});
      m.sph_resolutions = rd.positive_list(rd.require(runs["sph"], "runs.sph", "resolutions"),
                                           "runs.sph.resolutions");
    }
    if (runs["openfoam"]) {
      rd.check_keys(runs["openfoam"], "runs.openfoam", {"cell_sizes"});
      m.foam_cell_sizes = rd.positive_list(
          rd.require(runs["openfoam"], "runs.openfoam", "cell_sizes"), "runs.openfoam.cell_sizes");
    }
  }
  // A known failure must name a result of the runs section, so a typo cannot excuse nothing.
  std::vector<std::string> labels;
  for (const double dp : m.sph_resolutions) labels.push_back(sph_label(dp));
  for (const double dx : m.foam_cell_sizes) labels.push_back(foam_label(dx));
  for (std::size_t i = 0; i < m.targets.size(); ++i) {
    for (std::size_t j = 0; j < m.targets[i].known_failures.size(); ++j) {
      const std::string& label = m.targets[i].known_failures[j];
      if (std::find(labels.begin(), labels.end(), label) != labels.end()) continue;
      std::string list;
      for (const auto& l : labels) list += (list.empty() ? "" : ", ") + l;
      rd.fail(
          root["targets"][i]["known_failures"][j],
          "targets[" + std::to_string(i) + "].known_failures[" + std::to_string(j) + "]",
          "'" + label + "' is not a result of the runs section (expected one of: " + list + ")");
    }
  }
  m.results_dir = resolve(m.dir, root["results"] ? rd.text(root["results"], "results") : "results");
  return m;
}

std::string find_manifest(const std::string& name, const std::string& search_root) {
  std::vector<fs::path> tried;
  auto candidates = [&](const fs::path& base) { tried.push_back(base / "validation.yaml"); };
  const fs::path given(name);
  if (fs::is_regular_file(given)) return given.string();
  candidates(given);
  if (!search_root.empty()) candidates(fs::path(search_root) / "validation" / name);
  std::vector<std::string> listed;
  for (const auto& t : tried) {
    if (fs::is_regular_file(t)) return t.string();
    listed.push_back(t.string());
  }
  // Then Swell's own manifests: $SWELL_HOME, the install prefix, the source tree.
  if (given.is_relative() && !name.empty()) {
    const auto found =
        find_data_file((fs::path("validation") / name / "validation.yaml").string(), &listed);
    if (found && fs::is_regular_file(*found)) return found->string();
  }
  throw ManifestError("no validation manifest for '" + name + "' (tried " + tried_list(listed) +
                      "); " + data_roots_hint());
}

CaseSpec load_manifest_case(const Manifest& m, double dp, double end_time) {
  const bool edit = dp > 0.0 || end_time > 0.0 || m.end_time || !m.extra_gauges_yaml.empty();
  if (!edit) return load_case_file(m.case_file, m.case_sets);
  // Edit the YAML and re-read it with the ordinary reader, so every override is validated
  // exactly like a hand-written case file.
  YAML::Node root;
  try {
    root = YAML::LoadFile(m.case_file);
  } catch (const YAML::Exception& e) {
    return load_case_file(m.case_file);  // the case reader gives the precise message
  }
  // Command-line edits first, so the manifest's dp, end time and gauges still apply.
  if (!m.case_sets.empty()) {
    load_case_file(m.case_file);  // the unedited file's own errors first, with its lines
    root = YAML::Load(edit_case_text(YAML::Dump(root), m.case_sets, m.case_file));
  }
  if (dp > 0.0) root["dp"] = dp;
  const double t_end = end_time > 0.0 ? end_time : (m.end_time ? *m.end_time : -1.0);
  if (t_end > 0.0) root["time"]["end"] = t_end;
  if (!m.extra_gauges_yaml.empty()) {
    const YAML::Node extra = YAML::Load(m.extra_gauges_yaml);
    if (!root["gauges"]) root["gauges"] = YAML::Node(YAML::NodeType::Sequence);
    for (const auto& g : extra) root["gauges"].push_back(g);
  }
  YAML::Emitter out;
  out << root;
  // Labelled with the case file's path, so mesh files resolve as for the original; line
  // numbers in errors then refer to the edited text.
  return parse_case_text(out.c_str(), m.case_file);
}

}  // namespace swell
