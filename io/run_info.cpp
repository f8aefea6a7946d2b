#include "io/run_info.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "io/vtk_writer.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

std::string number(double v, const char* format) {
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

Provenance read_provenance(const YAML::Node& n) {
  Provenance p;
  auto text = [&](const char* key, std::string& to) {
    if (n[key]) to = n[key].as<std::string>();
  };
  text("version", p.version);
  text("commit", p.commit);
  text("compiler", p.compiler);
  text("build", p.build);
  text("command", p.command);
  text("date", p.date);
  text("host", p.host);
  text("cpu", p.cpu);
  text("recovered", p.recovered);
  if (n["threads"]) p.threads = n["threads"].as<int>();
  if (n["ranks"]) p.ranks = n["ranks"].as<int>();
  return p;
}

}  // namespace

std::string utc_minutes_now() {
  const std::time_t t = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&t, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &utc);
  return buf;
}

RunInfo read_run_info(const std::string& dir) {
  RunInfo info;
  const fs::path file = fs::path(dir) / "run_info.yaml";
  if (!fs::exists(file)) return info;
  try {
    const YAML::Node n = YAML::LoadFile(file.string());
    if (n["kind"]) info.kind = n["kind"].as<std::string>();
    if (n["resolution"]) info.resolution = n["resolution"].as<double>();
    if (n["wall_seconds"]) info.wall_seconds = n["wall_seconds"].as<double>();
    if (n["size"]) info.size = n["size"].as<long>();
    if (n["end_time"]) info.end_time = n["end_time"].as<double>();
    if (n["date"]) info.date = n["date"].as<std::string>();
    if (n["note"]) info.note = n["note"].as<std::string>();
    if (const YAML::Node p = n["provenance"]; p && p.IsSequence())
      for (const auto& e : p) info.provenance.push_back(read_provenance(e));
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
  return info;
}

void write_run_info(const std::string& dir, const RunInfo& info) {
  fs::create_directories(dir);
  std::ostringstream out;
  out << "# "
      << (info.header.empty() ? "how the files next to this one were produced" : info.header)
      << "\n";
  out << "kind: " << info.kind << "\n";
  if (info.resolution > 0.0)
    out << "resolution: " << number(info.resolution, "%.10g") << "   # dp or cell size [m]\n";
  if (std::isfinite(info.wall_seconds))
    out << "wall_seconds: " << number(info.wall_seconds, "%.4g") << "\n";
  if (info.size > 0) out << "size: " << info.size << "   # particles (sph) or cells (openfoam)\n";
  if (std::isfinite(info.end_time)) out << "end_time: " << number(info.end_time, "%.10g") << "\n";
  if (!info.date.empty()) out << "date: " << quoted_string(info.date) << "\n";
  if (!info.note.empty()) out << "note: " << quoted_string(info.note) << "\n";
  if (!info.provenance.empty()) {
    out << "provenance:   # one entry per command that wrote here (the first, then each restart)\n";
    for (const Provenance& p : info.provenance) {
      std::string block = provenance_yaml(p, 4);
      block.replace(0, 4, "  - ");
      out << block;
    }
  }
  write_file_atomically((fs::path(dir) / "run_info.yaml").string(), out.str());
}

}  // namespace swell
