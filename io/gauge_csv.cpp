#include "io/gauge_csv.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "io/vtk_writer.hpp"

namespace swell {

GaugeCsvFile::GaugeCsvFile(const std::string& path, const std::vector<std::string>& comment,
                           const std::vector<std::string>& columns, double resume_after)
    : path_(path), columns_(columns.size()) {
  if (resume_after >= 0.0 && std::filesystem::exists(path)) {
    // Keep the header and every row up to the checkpoint time; rewrite atomically.
    std::ifstream in(path);
    std::ostringstream kept;
    std::string line;
    while (std::getline(in, line)) {
      const bool data = !line.empty() && line[0] != '#' && line.rfind("time", 0) != 0;
      if (data) {
        double t = 0.0;
        // Times are printed with 9 digits: compare with that resolution.
        if (std::sscanf(line.c_str(), "%lf", &t) != 1 || t > resume_after * (1.0 + 1e-8) + 1e-12)
          continue;
      }
      kept << line << '\n';
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
  std::snprintf(buf, sizeof(buf), "%.9g", time);
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
