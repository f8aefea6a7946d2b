// Gauge CSV files: header with units, values read back as written (9 significant digits, the
// time 12), empty cells for gauges not due, and a resumed file that drops rows after the restart
// time, also at long times and in files written with 9-digit times.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/gauge_csv.hpp"

namespace swell {
namespace {

std::vector<std::vector<std::string>> read_cells(const std::string& path,
                                                 std::vector<std::string>* header) {
  std::ifstream f(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    if (line.back() == ',') cells.emplace_back();
    if (line.rfind("time", 0) == 0)
      *header = cells;
    else
      rows.push_back(cells);
  }
  return rows;
}

TEST(GaugeCsv, RoundTripWithUnitsAndEmptyCells) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "swell_gauge_csv.csv").string();
  {
    GaugeCsvFile f(path, {"test file"}, {"P1 [Pa]", "P2 [Pa]"});
    f.write_row(0.0, {1234.5678912345, -1.0}, {true, true});
    f.write_row(0.001, {0.000123456789, 0.0}, {true, false});
    f.write_row(0.002, {std::nan(""), 2.5}, {true, true});
  }
  std::vector<std::string> header;
  auto rows = read_cells(path, &header);
  ASSERT_EQ(header, (std::vector<std::string>{"time [s]", "P1 [Pa]", "P2 [Pa]"}));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_NEAR(std::stod(rows[0][1]), 1234.5678912345, 1e-5);  // 9 significant digits
  EXPECT_EQ(std::stod(rows[0][2]), -1.0);
  EXPECT_NEAR(std::stod(rows[1][1]), 0.000123456789, 1e-14);
  EXPECT_EQ(rows[1][2], "");  // not due: empty cell
  EXPECT_TRUE(std::isnan(std::stod(rows[2][1])));

  // Resume after t = 0.001: the t = 0.002 row goes, the header stays, new rows append.
  {
    GaugeCsvFile f(path, {"test file"}, {"P1 [Pa]", "P2 [Pa]"}, 0.001);
    f.write_row(0.0015, {7.0, 8.0}, {true, true});
  }
  rows = read_cells(path, &header);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(std::stod(rows[2][0]), 0.0015);
  EXPECT_EQ(std::stod(rows[2][2]), 8.0);
  EXPECT_EQ(header.size(), 3u);
}

// A per-step series at t ~ 1e4 s (dt 5e-5 s): every row keeps its own time, and a restart keeps
// exactly the rows up to the checkpoint. (With 9-digit times the rows 1e-4 s apart printed the
// same time, and the restart kept two rows written after the checkpoint.)
TEST(GaugeCsv, LongRunsKeepStepTimesApartAndResumeAtTheCheckpoint) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "swell_gauge_csv_long.csv").string();
  const double t0 = 1.0e4, dt = 5.0e-5;
  {
    GaugeCsvFile f(path, {"test file"}, {"R [m]"});
    for (int k = 0; k <= 10; ++k) f.write_row(t0 + k * dt, {0.1 * k}, {true});
  }
  std::vector<std::string> header;
  auto rows = read_cells(path, &header);
  ASSERT_EQ(rows.size(), 11u);
  for (int k = 0; k <= 10; ++k) EXPECT_NEAR(std::stod(rows[k][0]), t0 + k * dt, 1e-8) << k;
  {
    GaugeCsvFile f(path, {"test file"}, {"R [m]"}, t0 + 5 * dt);
    f.write_row(t0 + 6 * dt, {-1.0}, {true});
  }
  rows = read_cells(path, &header);
  ASSERT_EQ(rows.size(), 7u);  // k = 0..5, then the resumed run's first row
  EXPECT_NEAR(std::stod(rows[5][0]), t0 + 5 * dt, 1e-8);
  EXPECT_EQ(std::stod(rows[6][1]), -1.0);
}

// A file written with 9-digit times (before 2026-12-07), resumed by this build: the row at the
// checkpoint time, printed rounded up, stays; the next one goes.
TEST(GaugeCsv, NineDigitFilesResumeAsBefore) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "swell_gauge_csv_old.csv").string();
  {
    std::ofstream f(path);
    f << "# test file\ntime [s],P1 [Pa]\n0.100000000,1\n0.123456790,2\n0.123556790,3\n";
  }
  {
    GaugeCsvFile f(path, {"test file"}, {"P1 [Pa]"}, 0.1234567896);  // printed 0.12345679
    f.write_row(0.124, {4.0}, {true});
  }
  std::vector<std::string> header;
  const auto rows = read_cells(path, &header);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][1], "2");
  EXPECT_EQ(std::stod(rows[2][0]), 0.124);
}

}  // namespace
}  // namespace swell
