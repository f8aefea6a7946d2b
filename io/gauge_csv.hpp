// Gauge series as CSV: one file per gauge kind, a time column and one column per gauge
// quantity, SI units in the header. A resumed (restarted) run keeps the rows up to the
// checkpoint time and appends after them, so the file reads as if the run never stopped.
#pragma once

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "case/spec.hpp"

namespace swell {

// The CSV columns of a gauge (name and SI unit per quantity), the same for SPH runs, `swell
// probe` and converted OpenFOAM runs, so `swell compare` reads them alike.
std::vector<std::string> gauge_columns(const GaugeSpec& g, int dim);

// The time column's text, for the run's gauge files, their restart and `swell probe`: 12
// significant digits (values have 9), so a per-step series keeps its steps apart at long times.
inline int format_gauge_time(char* buf, std::size_t size, double t) {
  return std::snprintf(buf, size, "%.12g", t);
}

class GaugeCsvFile {
 public:
  // Creates `path` with `comment` lines (written as "# ...") and the column header
  // "time [s],<columns...>". With `resume_after` >= 0 an existing file is kept up to that
  // time instead (rows with a later time are dropped) and the header is not rewritten.
  GaugeCsvFile(const std::string& path, const std::vector<std::string>& comment,
               const std::vector<std::string>& columns, double resume_after = -1.0);

  // One row; a column whose `present` flag is false (gauge not due at this time) stays empty.
  void write_row(double time, const std::vector<double>& values, const std::vector<bool>& present);
  // Writes the buffered rows. This and write_row throw naming the file and the system's
  // reason once a write has failed (disk full, file size limit).
  void flush();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::size_t columns_ = 0;
  int error_ = 0;  // errno of the first failed write
  void check();
};

}  // namespace swell
