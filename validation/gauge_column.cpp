#include "validation/gauge_column.hpp"

#include <sstream>
#include <stdexcept>

#include "validation/metrics.hpp"

namespace swell::waves {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

}  // namespace

GaugeColumn read_gauge_column(const std::string& path, const std::string& column) {
  SeriesTable table;
  try {
    table = read_series_table(path);
  } catch (const std::exception& e) {
    throw std::invalid_argument(e.what());  // a bad file is bad input
  }
  // "H1 [m]" -> name "H1", unit "m".
  std::string name = column, unit;
  const auto open = column.rfind('['), close = column.rfind(']');
  if (open != std::string::npos && close != std::string::npos && close > open) {
    unit = column.substr(open + 1, close - open - 1);
    name = column.substr(0, open);
    while (!name.empty() && name.back() == ' ') name.pop_back();
  }
  const int c = table.find(name);
  if (c < 0) {
    std::string have;
    for (const auto& n : table.columns) have += (have.empty() ? "" : ", ") + n;
    throw std::invalid_argument(path + ": no gauge column '" + column + "' (columns: " + have +
                                ")");
  }
  if (!unit.empty() && unit != table.units[c])
    throw std::invalid_argument(path + ": gauge column '" + name + "' is in [" + table.units[c] +
                                "], not [" + unit + "]");
  const Series s = table.series(name);
  GaugeColumn g;
  g.file = path;
  g.name = name;
  g.unit = table.units[c];
  g.t = s.t;
  g.eta = s.v;
  if (g.t.size() < 2)
    throw std::invalid_argument(path + ": gauge column '" + name + "' holds " +
                                std::to_string(g.t.size()) + " values, at least 2 needed");
  for (std::size_t i = 1; i < g.t.size(); ++i)
    if (!(g.t[i] > g.t[i - 1]))
      throw std::invalid_argument(path + ": times must increase, but t = " + num(g.t[i]) +
                                  " follows t = " + num(g.t[i - 1]) + " (gauge '" + name + "')");
  return g;
}

}  // namespace swell::waves
