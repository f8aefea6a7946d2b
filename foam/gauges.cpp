// `swell foam`, part 4: OpenFOAM's postProcessing/ output -> gauges_<kind>.csv, in the format
// and with the column names of an SPH run (run/gauge_set.cpp), so the two compare directly.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>

#include "foam/foam.hpp"
#include "foam/plan.hpp"
#include "io/gauge_csv.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;
using foam::Plan;
using foam::Probe;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Times are keyed at 1e-9 s so rows of different function objects at the same time merge.
long long time_key(double t) {
  return std::llround(t * 1e9);
}

// Numeric subfolders of `dir` (time or start-time folders), sorted by time.
std::vector<std::pair<double, fs::path>> time_dirs(const fs::path& dir) {
  std::vector<std::pair<double, fs::path>> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_directory()) continue;
    const std::string n = e.path().filename().string();
    char* end = nullptr;
    const double t = std::strtod(n.c_str(), &end);
    if (!n.empty() && end && *end == '\0') out.emplace_back(t, e.path());
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

// Numbers of a line with parentheses and tabs treated as blanks.
std::vector<double> numbers(std::string line) {
  for (char& c : line)
    if (c == '(' || c == ')' || c == '\t') c = ' ';
  std::istringstream in(line);
  std::vector<double> v;
  std::string tok;
  while (in >> tok) v.push_back(std::strtod(tok.c_str(), nullptr));
  return v;
}

// A time-series file written by probes or forces: '#' comments, then "time values...". Files
// of later start times (a continued run) replace the rows from their start on.
std::map<long long, std::pair<double, std::vector<double>>> read_series(const fs::path& fo_dir,
                                                                        const std::string& file) {
  std::map<long long, std::pair<double, std::vector<double>>> rows;
  for (const auto& [start, dir] : time_dirs(fo_dir)) {
    std::ifstream in(dir / file);
    if (!in) continue;
    rows.erase(rows.lower_bound(time_key(start)), rows.end());
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      auto v = numbers(line);
      if (v.empty()) continue;
      const double t = v[0];
      v.erase(v.begin());
      rows[time_key(t)] = {t, std::move(v)};
    }
  }
  return rows;
}

// The "# Probe i (x y z)" header lines of a probes file, one list per time folder that holds
// the file (a continued run writes a new folder). interFoam (v1912) lists every location of its
// dictionary; one it finds in no cell is marked "# Not Found" and its column holds -VGREAT.
std::vector<std::vector<std::string>> probe_headers(const fs::path& fo_dir,
                                                    const std::string& file) {
  std::vector<std::vector<std::string>> out;
  for (const auto& [start, dir] : time_dirs(fo_dir)) {
    std::ifstream in(dir / file);
    if (!in) continue;
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line) && !line.empty() && line[0] == '#')
      if (line.rfind("# Probe ", 0) == 0) lines.push_back(line);
    out.push_back(std::move(lines));
  }
  return out;
}

// A raw set file: one "x y z alpha" line per point found in the mesh; points in case axes.
std::vector<std::array<double, 4>> read_set(const Plan& plan, const fs::path& file) {
  std::vector<std::array<double, 4>> pts;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto v = numbers(line);
    if (v.size() < 4) continue;
    const Eigen::Vector3d x = plan.foam(Eigen::Vector3d(v[0], v[1], v[2]));
    pts.push_back({x[0], x[1], x[2], v[3]});
  }
  return pts;
}

const char* kind_comment(GaugeSpec::Kind k) {
  switch (k) {
    case GaugeSpec::Kind::Pressure:
      return "pressure probes: interFoam static pressure p [Pa] of the cell holding the point; "
             "wall probes sample the first cell centre off the wall along the normal";
    case GaugeSpec::Kind::Height:
      return "water height: level: surface (default), the first height above the start of the "
             "line where alpha.water falls below 0.5 (interpolated); level: integral, the start "
             "+ the integral of alpha.water along the line to the tank top [m]";
    case GaugeSpec::Kind::Velocity:
      return "velocity probes: interFoam U [m/s] of the cell holding the point";
    case GaugeSpec::Kind::Force:
      return "force and moment of the fluid on the body's wall patches (forces function object; "
             "2D: per metre of width)";
    case GaugeSpec::Kind::Front:
      return "surge front: alpha.water >= 0.5 along the first cell row above the floor, from "
             "the water's start, + the fraction of the next cell [m]";
    case GaugeSpec::Kind::Runup:
      return "runup: not sampled by swell foam";
  }
  return "";
}

double height_from_set(const Probe& pr, int up, const std::vector<std::array<double, 4>>& pts) {
  const double z0 = pr.start[up], len = pr.end[up] - pr.start[up];
  const int n = pr.points;
  if (n < 2 || !(len > 0.0)) return kNaN;
  const double ds = len / (n - 1);
  std::vector<double> alpha(n, 0.0);
  for (const auto& p : pts) {
    const long k = std::lround((p[up] - z0) / ds);
    if (k >= 0 && k < n) alpha[k] = std::clamp(p[3], 0.0, 1.0);
  }
  return pr.spec.level == GaugeSpec::Level::Integral ? foam::level_integral(alpha, z0, ds)
                                                     : foam::level_surface(alpha, z0, ds);
}

}  // namespace

double foam::level_integral(const std::vector<double>& alpha, double z0, double ds) {
  const std::size_t n = alpha.size();
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) sum += (k == 0 || k + 1 == n ? 0.5 : 1.0) * alpha[k];
  return z0 + sum * ds;
}

// The first free surface above the start: from the first wet sample (alpha >= 0.5, one of the
// three lowest) up to where alpha first falls below 0.5, linearly interpolated. A dry
// start (a dry bed) reads z0.
double foam::level_surface(const std::vector<double>& alpha, double z0, double ds) {
  const std::size_t n = alpha.size();
  std::size_t k = 0;
  while (k < n && !(alpha[k] >= 0.5)) ++k;
  if (k == n || k > 2) return z0;  // dry at the bottom of the line
  for (; k + 1 < n; ++k)
    if (alpha[k + 1] < 0.5)
      return z0 + ds * (static_cast<double>(k) + (alpha[k] - 0.5) / (alpha[k] - alpha[k + 1]));
  return z0 + ds * static_cast<double>(n - 1);
}

double foam::front_from_row(const std::vector<double>& alpha, double x0, double dx) {
  const int n = static_cast<int>(alpha.size());
  int i = 0;
  while (i < n && !(alpha[i] >= 0.5)) ++i;
  if (i == n) return kNaN;
  int last = i;
  for (int j = i + 1; j < n; ++j) {
    if (std::isnan(alpha[j])) continue;
    if (alpha[j] >= 0.5) {
      last = j;
    } else {
      break;
    }
  }
  double front = x0 + (last + 1) * dx;
  if (last + 1 < n && !std::isnan(alpha[last + 1])) front += std::max(0.0, alpha[last + 1]) * dx;
  return front;
}

std::vector<std::string> convert_foam_gauges(const CaseSpec& spec, const FoamOptions& opt,
                                             const std::string& gauge_dir, std::ostream& log) {
  const Plan plan = foam::make_plan(spec, opt);
  const fs::path pp = fs::path(opt.out_dir) / "postProcessing";
  const int dim = spec.dim;
  const int up = plan.grid.up;
  const double width = dim == 2 ? plan.grid.cell[2] : 1.0;  // 2D: forces per metre of width
  fs::create_directories(gauge_dir);

  // Rows per kind: time key -> (time, values per gauge, each a vector of its columns).
  struct Column {
    std::vector<std::vector<double>> values;  // per gauge of the kind (empty: not sampled)
    double time = 0.0;
  };
  std::map<GaugeSpec::Kind, std::vector<const Probe*>> by_kind;
  for (const auto& pr : plan.probes)
    if (!pr.skipped) by_kind[pr.spec.kind].push_back(&pr);

  std::vector<std::string> written;
  for (const auto& [kind, members] : by_kind) {
    std::map<long long, Column> rows;
    // A structured binding cannot be captured by C++17 lambdas (clang 14 refuses it): a copy
    // of the count is.
    const std::size_t n_members = members.size();
    auto put = [&](std::size_t member, double t, std::vector<double> v) {
      t += plan.time_offset;  // OpenFOAM time -> case time
      Column& c = rows[time_key(t)];
      c.time = t;
      c.values.resize(n_members);
      c.values[member] = std::move(v);
    };
    for (std::size_t m = 0; m < members.size(); ++m) {
      const Probe& pr = *members[m];
      const fs::path fo = pp / pr.function;
      if (!fs::is_directory(fo)) {
        log << "  note: no output for gauge " << pr.spec.name << " (" << fo.string() << ")\n";
        continue;
      }
      switch (kind) {
        case GaugeSpec::Kind::Pressure:
        case GaugeSpec::Kind::Velocity: {
          // Position of this gauge among the probes of its function object, and their count.
          int index = 0, expected = 0;
          bool before = true;
          for (const auto& q : plan.probes) {
            if (&q == &pr) before = false;
            if (q.skipped || q.function != pr.function) continue;
            index += before;
            ++expected;
          }
          const bool vector = kind == GaugeSpec::Kind::Velocity;
          const std::string file = vector ? "U" : "p";
          // The header must list the case's locations: another count (output of an earlier
          // version of the case) would put the columns onto the wrong gauges, and a location
          // interFoam found in no cell has only -VGREAT. Either way the gauge is left out, said.
          std::string why;
          for (const auto& lines : probe_headers(fo, file)) {
            if (lines.empty()) continue;
            if (static_cast<int>(lines.size()) != expected)
              why = "declares " + std::to_string(lines.size()) +
                    " probe locations where the case has " + std::to_string(expected) +
                    " (written for another version of the case?), so its columns cannot be "
                    "matched to the gauges";
            else if (lines[static_cast<std::size_t>(index)].find("Not Found") != std::string::npos)
              why = "marks this gauge's location \"Not Found\" (in no cell of the mesh)";
          }
          if (!why.empty()) {
            log << "  warning: gauge " << pr.spec.name << " not converted: " << (fo / file).string()
                << " " << why << "\n";
            break;
          }
          const int stride = vector ? 3 : 1;
          for (const auto& [key, row] : read_series(fo, file)) {
            const auto& v = row.second;
            if (static_cast<int>(v.size()) < (index + 1) * stride) continue;
            std::vector<double> out(v.begin() + index * stride,
                                    v.begin() + index * stride + (vector ? dim : 1));
            if (vector && plan.z_up) out[1] = v[index * stride + 2];  // OpenFOAM's z: case y
            for (double& x : out)  // -VGREAT: a location interFoam did not find
              if (std::abs(x) >= 1e299) x = kNaN;
            put(m, row.first, std::move(out));
          }
          break;
        }
        case GaugeSpec::Kind::Height:
          for (const auto& [t, dir] : time_dirs(fo)) {
            const fs::path f = dir / (foam::foam_word(pr.spec.name) + "_alpha.water.xy");
            if (fs::exists(f)) put(m, t, {height_from_set(pr, up, read_set(plan, f))});
          }
          break;
        case GaugeSpec::Kind::Front:
          for (const auto& [t, dir] : time_dirs(fo)) {
            double front = kNaN;
            bool any = false;
            for (std::size_t l = 0; l < pr.line_starts.size(); ++l) {
              const fs::path f = dir / (foam::foam_word(pr.spec.name) + "_" + std::to_string(l) +
                                        "_alpha.water.xy");
              if (!fs::exists(f)) continue;
              any = true;
              const double x0 = pr.line_starts[l][0], dx = plan.grid.cell[0];
              std::vector<double> alpha(static_cast<std::size_t>(pr.points), kNaN);
              for (const auto& p : read_set(plan, f)) {
                const long i = std::lround((p[0] - x0) / dx);
                if (i >= 0 && i < pr.points) alpha[i] = p[3];
              }
              const double f_l = foam::front_from_row(alpha, x0 - 0.5 * dx, dx);
              if (std::isfinite(f_l)) front = std::isfinite(front) ? std::max(front, f_l) : f_l;
            }
            if (any) put(m, t, {front});
          }
          break;
        case GaugeSpec::Kind::Force: {
          const auto forces = read_series(fo, "force.dat");
          const auto moments = read_series(fo, "moment.dat");
          for (const auto& [key, row] : forces) {
            const auto mit = moments.find(key);
            if (row.second.size() < 3 || mit == moments.end() || mit->second.second.size() < 3)
              continue;
            // Case axes. The y <-> z swap of Plan::z_up is a reflection, so the moment (an
            // axial vector) also changes sign: case M_z = -OpenFOAM M_y.
            const double sign = plan.z_up ? -1.0 : 1.0;
            const Eigen::Vector3d f = plan.foam({row.second[0], row.second[1], row.second[2]});
            const Eigen::Vector3d mo =
                sign *
                plan.foam({mit->second.second[0], mit->second.second[1], mit->second.second[2]});
            std::vector<double> v;
            for (int d = 0; d < dim; ++d) v.push_back(f[d] / width);
            if (dim == 2) {
              v.push_back(mo[2] / width);
            } else {
              for (int d = 0; d < 3; ++d) v.push_back(mo[d]);
            }
            put(m, row.first, std::move(v));
          }
          break;
        }
        case GaugeSpec::Kind::Runup:  // skipped by the plan
          break;
      }
    }

    std::vector<std::string> columns;
    std::vector<std::size_t> first;
    for (const Probe* pr : members) {
      first.push_back(columns.size());
      for (auto& c : gauge_columns(pr->spec, dim)) columns.push_back(c);
    }
    std::ostringstream first_line;
    first_line << "swell foam gauges (interFoam), case " << spec.name << ", cell " << plan.cell_size
               << " m";
    std::vector<std::string> comment{first_line.str(), kind_comment(kind)};
    for (const auto& pr : plan.probes)
      if (pr.skipped && pr.spec.kind == kind)
        comment.push_back("gauge " + pr.spec.name + " not sampled (see the swell foam notes)");
    const std::string path =
        (fs::path(gauge_dir) / (std::string("gauges_") + gauge_kind_name(kind) + ".csv")).string();
    GaugeCsvFile csv(path, comment, columns);
    std::vector<double> values(columns.size());
    std::vector<bool> present(columns.size());
    for (const auto& [key, c] : rows) {
      std::fill(present.begin(), present.end(), false);
      for (std::size_t m = 0; m < c.values.size(); ++m)
        for (std::size_t k = 0; k < c.values[m].size(); ++k) {
          values[first[m] + k] = c.values[m][k];
          present[first[m] + k] = true;
        }
      csv.write_row(c.time, values, present);
    }
    csv.flush();
    written.push_back(path);
    log << "  " << path << ": " << rows.size() << " rows\n";
  }
  return written;
}

}  // namespace swell
