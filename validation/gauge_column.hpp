// A gauge column read from a CSV file for the wave analysis (`swell waves analyse`,
// `swell waves predict`): the file reading that waves/analysis.hpp, pure maths, leaves out.
#pragma once

#include <string>
#include <vector>

namespace swell::waves {

struct GaugeColumn {
  std::string file, name, unit;  // name without its unit; unit as in "[unit]", "" if none
  std::vector<double> t, eta;    // rows with an empty or NaN cell dropped
};

// One column of a CSV gauge file (Swell's gauges_*.csv: '#' comment lines, a header
// `time [s],H1 [m],...`, numeric rows; read by swell::read_series_table). `column` is its name
// with or without the unit suffix ("H1" or "H1 [m]"). Every problem is std::invalid_argument
// naming the file: unreadable, malformed (with its line and what was expected), no such column
// (with the columns present), a unit that differs, fewer than two values, times not increasing.
GaugeColumn read_gauge_column(const std::string& path, const std::string& column);

}  // namespace swell::waves
