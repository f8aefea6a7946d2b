// `swell verify`: the method checked piece by piece (issue #14). Each verification is a plain
// function that measures and returns a Result; the runner (apps/verify_command) writes its
// tables as CSV, its plots as PNG (verify/plot_verify.py), and report.md with every figure.
//
// A verification states each measured figure with the bound it must meet (or "report" where
// the figure is shown, not judged); ctest runs the fast form (Options::full = false) and
// asserts every bound; `swell verify --full` runs the convergence studies at more resolutions.
#pragma once

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace swell::verify {

// One measured number and the bound it is held to.
struct Figure {
  enum class Rel { AtMost, AtLeast, Report };
  std::string name;  // what was measured, e.g. "L1 error of rho, N = 400"
  double value = std::numeric_limits<double>::quiet_NaN();
  Rel rel = Rel::Report;
  double bound = std::numeric_limits<double>::quiet_NaN();
  std::string unit;  // "" when dimensionless
  bool pass() const {
    if (!std::isfinite(value)) return false;  // a measurement that failed never passes
    switch (rel) {
      case Rel::AtMost:
        return value <= bound;
      case Rel::AtLeast:
        return value >= bound;
      case Rel::Report:
        return true;
    }
    return false;
  }
};
inline Figure at_most(std::string name, double value, double bound, std::string unit = "") {
  return {std::move(name), value, Figure::Rel::AtMost, bound, std::move(unit)};
}
inline Figure at_least(std::string name, double value, double bound, std::string unit = "") {
  return {std::move(name), value, Figure::Rel::AtLeast, bound, std::move(unit)};
}
inline Figure report(std::string name, double value, std::string unit = "") {
  return {std::move(name), value, Figure::Rel::Report, std::numeric_limits<double>::quiet_NaN(),
          std::move(unit)};
}

// Least-squares slope of log(err) against log(x): the fitted order (an error falling as x^k
// has order k; against a particle number n, err ~ n^-k gives -k).
template <class V>
double fitted_order(const V& x, const V& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(err[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// A table of numbers, written as NAME/<file>.csv (header = columns).
struct Table {
  std::string file;                       // file stem, e.g. "gradient_convergence"
  std::vector<std::string> columns;       // with units in brackets, e.g. "h [m]"
  std::vector<std::vector<double>> rows;  // each row has columns.size() values
};

// A figure drawn from a table: x column against one or more y columns.
struct Plot {
  std::string file;  // PNG stem, e.g. "gradient_convergence"
  std::string title;
  std::string table;  // Table::file it reads
  std::string x;      // column name
  std::vector<std::string> y;
  bool log_x = false, log_y = false;
  std::string style = "lines";  // "lines", "points" or "lines+points"
};

struct Result {
  std::vector<Figure> figures;
  std::vector<Table> tables;
  std::vector<Plot> plots;
  std::string notes;  // markdown paragraph(s) for report.md: method, set-up, what to read
  bool passed() const {
    for (const auto& f : figures)
      if (!f.pass()) return false;
    return true;
  }
};

struct Options {
  std::filesystem::path outdir;  // this verification's own folder (the runner creates it)
  bool full = false;             // the full convergence study (longer) instead of the fast one
  int threads = 1;
};

struct Verification {
  const char* name;   // command-line name, e.g. "sod"
  const char* title;  // one line for --list and report.md
  Result (*run)(const Options&);
};

// Every verification, in report order (verify/registry.cpp).
const std::vector<Verification>& all();

}  // namespace swell::verify
