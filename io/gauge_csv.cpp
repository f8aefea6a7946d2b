#include "io/gauge_csv.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "io/vtk_writer.hpp"

namespace swell {

namespace {

// Significant digits of a row's printed time (its first cell).
int time_digits(const std::string& line) {
  int digits = 0;
  bool leading = true;
  for (const char c : line) {
    if (c == ',' || c == 'e' || c == 'E') break;
    if (c < '0' || c > '9') continue;  // sign, decimal point
    if (leading && c == '0') continue;
    leading = false;
    ++digits;
  }
  return digits;
}

}  // namespace

GaugeCsvFile::GaugeCsvFile(const std::string& path, const std::vector<std::string>& comment,
                           const std::vector<std::string>& columns, double resume_after)
    : path_(path), columns_(columns.size()) {
  if (resume_after >= 0.0 && std::filesystem::exists(path)) {
    // Keep the header and every row up to the checkpoint time; rewrite atomically. Times are
    // printed with 12 significant digits (write_row); files written before 2026-12-07 have 9.
    // A file with a time of 10 or more digits was written with 12: a row is kept where its
    // printed time is at most the checkpoint time printed the same way (rounding is monotonic,
    // so every row up to the checkpoint stays and every later one goes unless it lies within
    // 5e-13 relative of it). Otherwise (9-digit files, and files whose times all print short,
    // e.g. interval rows at round times) the 9-digit files' rule: up to 1e-8 relative above.
    // (A 9-digit file resumed by this build and then again after 12-digit rows were added
    // takes the 12-digit rule for its old rows too: its row at the first checkpoint, if
    // printed rounded up, is then dropped.)
    const auto is_data = [](const std::string& l) {
      return !l.empty() && l[0] != '#' && l.rfind("time", 0) != 0;
    };
    std::ifstream in(path);
    std::vector<std::string> lines;
    std::string line;
    bool twelve = false;
    while (std::getline(in, line)) {
      lines.push_back(line);
      if (is_data(line) && time_digits(line) >= 10) twelve = true;
    }
    char buf[40];
    format_gauge_time(buf, sizeof(buf), resume_after);
    const double last = twelve ? std::strtod(buf, nullptr) : resume_after * (1.0 + 1e-8) + 1e-12;
    std::ostringstream kept;
    for (const auto& l : lines) {
      if (is_data(l)) {
        double t = 0.0;
        if (std::sscanf(l.c_str(), "%lf", &t) != 1 || t > last) continue;
      }
      kept << l << '\n';
    }
    write_file_atomically(path, kept.str());
    out_.open(path, std::ios::app);
  } else {
    out_.open(path, std::ios::trunc);
    for (const auto& c : comment) out_ << "# " << c << '\n';
    out_ << "time [s]";
    for (const auto& c : columns) out_ << ',' << c;
    out_ << '\n';
  }
  if (!out_) throw std::runtime_error("cannot write gauge file " + path);
}

void GaugeCsvFile::check() {
  // errno is read right after the failing write (the buffer spills inside write_row).
  if (!out_) {
    if (error_ == 0) error_ = errno != 0 ? errno : EIO;
    throw std::runtime_error("cannot write gauge file " + path_ + ": " + std::strerror(error_));
  }
}

void GaugeCsvFile::flush() {
  if (out_) out_.flush();
  check();
}

void GaugeCsvFile::write_row(double time, const std::vector<double>& values,
                             const std::vector<bool>& present) {
  char buf[40];
  format_gauge_time(buf, sizeof(buf), time);
  out_ << buf;
  for (std::size_t c = 0; c < columns_; ++c) {
    out_ << ',';
    if (c < values.size() && present[c]) {
      std::snprintf(buf, sizeof(buf), "%.9g", values[c]);
      out_ << buf;
    }
  }
  out_ << '\n';
  check();
}

std::vector<std::string> gauge_columns(const GaugeSpec& g, int dim) {
  static const char* axes[] = {"x", "y", "z"};
  std::vector<std::string> c;
  switch (g.kind) {
    case GaugeSpec::Kind::Pressure:
      c.push_back(g.name + " [Pa]");
      break;
    case GaugeSpec::Kind::Height:
    case GaugeSpec::Kind::Front:
      c.push_back(g.name + " [m]");
      break;
    case GaugeSpec::Kind::Runup:  // the CSV says whether relative to a still-water level
      c.push_back(g.name + (g.swl ? " above swl [m]" : " elevation [m]"));
      break;
    case GaugeSpec::Kind::Velocity:
      for (int d = 0; d < dim; ++d) c.push_back(g.name + "_v" + axes[d] + " [m/s]");
      break;
    case GaugeSpec::Kind::Force: {
      const std::string fu = dim == 2 ? " [N/m]" : " [N]", mu = dim == 2 ? " [N m/m]" : " [N m]";
      for (int d = 0; d < dim; ++d) c.push_back(g.name + "_f" + axes[d] + fu);
      if (dim == 2) {
        c.push_back(g.name + "_mz" + mu);
      } else {
        for (int d = 0; d < 3; ++d) c.push_back(g.name + "_m" + axes[d] + mu);
      }
      break;
    }
  }
  return c;
}

}  // namespace swell
