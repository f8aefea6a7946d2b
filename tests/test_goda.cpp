// waves/goda: Goda's wave pressures on a vertical wall (Goda 1974, 2000; Takahashi et al. 1994)
// against a worked example and identities of the formula that a transcription error breaks, and
// `swell waves goda` (apps/goda_command).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "apps/goda_command.hpp"
#include "waves/dispersion.hpp"
#include "waves/goda.hpp"

namespace swell::waves {
namespace {

constexpr double kPi = std::numbers::pi;

// A composite breakwater with every term at work: a mound (d < h' < h), h_b > h (the depth
// 5 H1/3 seaward, on a sloping bed), oblique waves and a crest below eta* (overtopping), uplift.
//   H = 6 m, T = 11 s, h = 15 m, h' = 10 m, d = 8.5 m, h_b = 16.5 m, h_c = 4 m, beta = 15 deg,
//   rho = 1030 kg/m^3, g = 9.81 m/s^2, B = 16 m.
// No published worked example was found in the reference corpora available to this project
// (CEM VI-5, Goda 2000 ch. 4 and CETN-III-38 were searched for; their example pages were not
// reachable), so the expected values are a hand calculation, written out step by step and
// evaluated independently of waves/goda.cpp (Python, L by bisection on the dispersion relation):
//   L = 122.2917 m (kh = 0.770680); 4 pi h / L = 1.54136, sinh = 2.22846, ratio 0.69167,
//   alpha1 = 0.6 + 0.5 * 0.47841 = 0.839212;
//   alpha2 = min((16.5 - 8.5) / (3 * 16.5) * (6 / 8.5)^2, 2 * 8.5 / 6) = min(0.0805285, 2.83);
//   alpha3 = 1 - (10/15) (1 - 1/cosh 0.770680) = 0.841476;
//   eta* = 0.75 (1 + cos 15) 6 = 8.84667 m, hc* = 4 m, alpha4 = 1 - 4/8.84667 = 0.547852;
//   p1 = 0.5 (1 + cos 15)(alpha1 + alpha2 cos^2 15) rho g H = 54488.5 Pa, p2 = p1 / cosh kh =
//   41531.9 Pa, p3 = 45850.8 Pa, p4 = 29851.7 Pa, pu = 42083.1 Pa;
//   P = (p1 + p3) h'/2 + (p1 + p4) hc*/2 = 670377 N/m, M = 4.57178e6 N m/m,
//   U = pu B / 2 = 336665 N/m, M_U = (2/3) U B = 3.59109e6 N m/m.
// Tolerance 1e-5 relative: the printed 6 digits.
TEST(Goda, WorkedExampleCompositeBreakwater) {
  GodaInput in;
  in.height = 6.0, in.period = 11.0, in.depth = 15.0, in.base_depth = 10.0, in.berm_depth = 8.5;
  in.breaking_depth = 16.5, in.freeboard = 4.0, in.beta_deg = 15.0, in.rho = 1030.0, in.g = 9.81;
  in.width = 16.0;
  const GodaPressure r = goda_pressure(in);
  const auto near = [](double v, double expected) { EXPECT_NEAR(v, expected, 1e-5 * expected); };
  near(r.length, 122.2917), near(r.kh, 0.770680);
  near(r.alpha1, 0.839212), near(r.alpha2, 0.0805285), near(r.alpha3, 0.841476);
  near(r.alpha4, 0.547852), near(r.eta_star, 8.84667), near(r.hc_star, 4.0);
  near(r.p1, 54488.5), near(r.p2, 41531.9), near(r.p3, 45850.8), near(r.p4, 29851.7);
  near(r.pu, 42083.1), near(r.force, 670377.0), near(r.moment, 4.57178e6);
  near(r.uplift_force, 336665.0), near(r.uplift_moment, 3.59109e6);
}

GodaInput flume(double H) {
  GodaInput in;
  in.height = H, in.period = 1.0, in.depth = 0.3;
  return in;
}

// The configurations the identities below run over: a plain wall, a mound, overtopping,
// oblique waves, modification factors.
std::vector<GodaInput> configurations() {
  std::vector<GodaInput> all;
  all.push_back(flume(0.045));
  GodaInput mound = flume(0.08);
  mound.base_depth = 0.22, mound.berm_depth = 0.15, mound.breaking_depth = 0.33;
  all.push_back(mound);
  GodaInput low = mound;
  low.freeboard = 0.05;  // below eta* = 0.12 m
  all.push_back(low);
  GodaInput oblique = low;
  oblique.beta_deg = 40.0, oblique.lambda1 = 0.8, oblique.lambda2 = 0.4, oblique.lambda3 = 0.7;
  all.push_back(oblique);
  GodaInput crest_at_swl = mound;
  crest_at_swl.freeboard = 0.0;
  all.push_back(crest_at_swl);
  return all;
}

TEST(Goda, DistributionIsContinuousAndHitsItsCorners) {
  for (const GodaInput& in : configurations()) {
    const GodaPressure r = goda_pressure(in);
    const double e = 1e-9 * r.p1;
    EXPECT_NEAR(r.pressure(-1e-12), r.p1, e);                      // continuous at the SWL
    if (r.hc_star > 0.0) EXPECT_NEAR(r.pressure(1e-12), r.p1, e);  // (no wall above a crest at SWL)
    EXPECT_NEAR(r.pressure(-r.input.base_depth), r.p3, e);
    EXPECT_NEAR(r.pressure(r.hc_star), r.p4, e);  // the crest, or eta* where p4 = 0
    // The line below the SWL passes through p2 at the bed: its slope is (p1 - p2) / h.
    const double z = -0.5 * r.input.base_depth;
    EXPECT_NEAR(r.pressure(z), r.p1 - (r.p1 - r.p2) * 0.5 * r.input.base_depth / in.depth, e);
    EXPECT_EQ(r.pressure(-r.input.base_depth - 1e-6), 0.0);  // below the base: no wall
    EXPECT_EQ(r.pressure(r.hc_star + 1e-6), 0.0);            // above the crest or eta*
    if (in.freeboard >= r.eta_star) EXPECT_EQ(r.p4, 0.0);
    if (in.freeboard < r.eta_star) EXPECT_GT(r.p4, 0.0);
  }
}

// Force and moment about the base by midpoint quadrature of p(z) (400,000 cells): the closed
// trapezoid forms must equal the integrals.
TEST(Goda, ForceAndMomentAreTheIntegralsOfTheDistribution) {
  for (const GodaInput& in : configurations()) {
    const GodaPressure r = goda_pressure(in);
    const double z0 = -r.input.base_depth, z1 = r.hc_star;
    const int n = 400000;
    double force = 0.0, moment = 0.0;
    for (int i = 0; i < n; ++i) {
      const double z = z0 + (i + 0.5) * (z1 - z0) / n;
      force += r.pressure(z) * (z1 - z0) / n;
      moment += r.pressure(z) * (z - z0) * (z1 - z0) / n;
    }
    EXPECT_NEAR(force, r.force, 1e-7 * r.force);
    EXPECT_NEAR(moment, r.moment, 1e-7 * r.moment);
    // The uplift triangle: U = pu B / 2 acting at B/3 from the toe, 2B/3 from the heel.
    GodaInput wide = in;
    wide.width = 2.0;
    const GodaPressure u = goda_pressure(wide);
    EXPECT_NEAR(u.uplift_force, 0.5 * u.pu * 2.0, 1e-12 * u.pu);
    EXPECT_NEAR(u.uplift_moment, u.uplift_force * 4.0 / 3.0, 1e-12 * u.pu);
    EXPECT_EQ(r.uplift_force, 0.0);  // no width given
  }
}

TEST(Goda, NoMoundMeansNoAlpha2AndP3IsTheBedPressure) {
  const GodaPressure r = goda_pressure(flume(0.045));
  EXPECT_EQ(r.alpha2, 0.0);  // d = h' = h = h_b
  EXPECT_NEAR(r.alpha3, 1.0 / std::cosh(r.kh), 1e-15);
  EXPECT_NEAR(r.p3, r.p2, 1e-12 * r.p2);
  EXPECT_NEAR(r.pu, r.p3, 1e-12 * r.p2);  // pu = a1 a3 rho g H = p3 for beta = 0, no mound
  // A mound makes alpha2 > 0 and raises p1 by alpha2 rho g H.
  GodaInput mound = flume(0.045);
  mound.base_depth = 0.25, mound.berm_depth = 0.2;
  const GodaPressure m = goda_pressure(mound);
  EXPECT_GT(m.alpha2, 0.0);
  EXPECT_NEAR(m.p1 - r.p1, m.alpha2 * 1000.0 * 9.81 * 0.045, 1e-9 * m.p1);
  // alpha2's two branches: (h - d)/(3h) (H/d)^2 for a deep berm, 2d/H for a shallow one.
  GodaInput shallow = flume(0.1);
  shallow.base_depth = 0.1, shallow.berm_depth = 0.02;
  EXPECT_NEAR(goda_pressure(shallow).alpha2, 2 * 0.02 / 0.1, 1e-15);
}

// H -> 0: the pressures are linear in H (alpha2 ~ H^2 vanishes, eta* ~ H), so p1 / (rho g H)
// tends to alpha1, which depends on T and h only, and the force per rho g H h to
// (1 + alpha3) alpha1 h' / (2h): the part above the SWL goes as H^2.
TEST(Goda, SmallWaveLimit) {
  GodaInput in = flume(1e-7);
  in.base_depth = 0.25, in.berm_depth = 0.2;
  const GodaPressure r = goda_pressure(in);
  const double k = wave_number(2 * kPi / 1.0, 0.3);
  const double alpha1 = 0.6 + 0.5 * std::pow(2 * k * 0.3 / std::sinh(2 * k * 0.3), 2);
  const double alpha3 = 1 - 0.25 / 0.3 * (1 - 1 / std::cosh(k * 0.3));
  const double rgh = 1000.0 * 9.81 * 1e-7;
  EXPECT_NEAR(r.p1 / rgh, alpha1, 1e-6);
  EXPECT_NEAR(r.eta_star / 1e-7, 1.5, 1e-12);
  EXPECT_NEAR(r.force / (rgh * 0.3), 0.5 * (1 + alpha3) * alpha1 * 0.25 / 0.3, 1e-6);
  EXPECT_NEAR(r.pressure(-0.1) / rgh, alpha1 * (1 - (1 - 1 / std::cosh(k * 0.3)) * 0.1 / 0.3),
              1e-6);
  GodaInput twice = in;
  twice.height = 2e-7;
  EXPECT_NEAR(goda_pressure(twice).p3 / r.p3, 2.0, 1e-6);
}

TEST(Goda, ObliquityAndModificationFactors) {
  GodaInput mound = flume(0.08);
  mound.base_depth = 0.22, mound.berm_depth = 0.15;
  const GodaPressure normal = goda_pressure(mound);
  GodaInput oblique = mound;
  oblique.beta_deg = 60.0;  // cos = 1/2
  const GodaPressure o = goda_pressure(oblique);
  EXPECT_NEAR(o.eta_star, 0.75 * normal.eta_star, 1e-15);
  EXPECT_NEAR(o.p1, 0.75 * (normal.alpha1 + 0.25 * normal.alpha2) * 1000 * 9.81 * 0.08,
              1e-12 * o.p1);
  EXPECT_NEAR(o.pu, 0.75 * normal.pu, 1e-12 * o.pu);
  GodaInput factors = mound;
  factors.lambda1 = 0.5, factors.lambda2 = 0.0, factors.lambda3 = 0.25;
  const GodaPressure f = goda_pressure(factors);
  EXPECT_NEAR(f.p1, 0.5 * normal.alpha1 * 1000 * 9.81 * 0.08, 1e-12 * f.p1);
  EXPECT_NEAR(f.eta_star, 0.5 * normal.eta_star, 1e-15);
  EXPECT_NEAR(f.pu, 0.25 * normal.pu, 1e-12 * f.pu);
}

TEST(Goda, BadInputNamesTheParameter) {
  const auto message = [](GodaInput in) {
    try {
      goda_pressure(in);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  GodaInput in = flume(0.045);
  in.height = 0.0;
  EXPECT_NE(message(in).find("H (wave height)"), std::string::npos);
  in = flume(0.045), in.base_depth = 0.4;
  EXPECT_NE(message(in).find("h' (depth of the caisson base): expected 0 < h' <= h, got 0.4"),
            std::string::npos);
  in = flume(0.045), in.berm_depth = 0.35;
  EXPECT_NE(message(in).find("d (depth above the berm)"), std::string::npos);
  in = flume(0.045), in.freeboard = -0.1;
  EXPECT_NE(message(in).find("h_c"), std::string::npos);
  in = flume(0.045), in.beta_deg = 90.0;
  EXPECT_NE(message(in).find("beta"), std::string::npos);
  in = flume(0.045), in.period = std::nan("");
  EXPECT_NE(message(in).find("T (period)"), std::string::npos);
  in = flume(0.045), in.lambda2 = -1.0;
  EXPECT_NE(message(in).find("lambda"), std::string::npos);
}

// `swell waves goda`: the report and the --csv table, whose linear interpolation is the
// distribution exactly (its rows hold the corners).
TEST(GodaCommand, ReportAndCsvTable) {
  WavesGodaOptions opt;
  opt.input = flume(0.045);
  opt.input.freeboard = 0.05;
  opt.input.base_depth = 0.25, opt.input.berm_depth = 0.2;
  opt.lambda = "1,1,0.5";
  const std::filesystem::path csv =
      std::filesystem::path(SWELL_BINARY_DIR) / "test_out" / "goda_table.csv";
  std::filesystem::create_directories(csv.parent_path());
  opt.csv = csv.string();
  std::ostringstream out;
  run_waves_goda(opt, out);
  const GodaPressure r = goda_pressure([&] {
    GodaInput in = opt.input;
    in.lambda3 = 0.5;
    return in;
  }());
  char force[64];
  std::snprintf(force, sizeof force, "%.6g N/m", r.force);
  EXPECT_NE(out.str().find(force), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("alpha2"), std::string::npos);

  std::ifstream in(csv);
  std::vector<double> z, p;
  double table_force = 0.0;
  for (std::string row; std::getline(in, row);) {
    if (row.rfind("# force [N/m]: ", 0) == 0) table_force = std::stod(row.substr(15));
    if (row.empty() || row[0] == '#' || row[0] == 'z') continue;
    const auto comma = row.find(',');
    z.push_back(std::stod(row.substr(0, comma)));
    p.push_back(std::stod(row.substr(comma + 1)));
  }
  EXPECT_NEAR(table_force, r.force, 1e-8 * r.force);
  ASSERT_GE(z.size(), 10u);
  EXPECT_NEAR(z.front(), -0.25, 1e-12);
  EXPECT_NEAR(z.back(), 0.05, 1e-12);
  for (double zz = -0.2499; zz < 0.05; zz += 0.0013) {
    std::size_t i = 1;
    while (z[i] < zz) ++i;
    const double s = (zz - z[i - 1]) / (z[i] - z[i - 1]);
    EXPECT_NEAR(p[i - 1] + s * (p[i] - p[i - 1]), r.pressure(zz), 1e-6 * r.p1) << zz;
  }

  opt.lambda = "1,2";
  EXPECT_THROW(run_waves_goda(opt, out), std::invalid_argument);
  opt.lambda = "1,x,1";
  EXPECT_THROW(run_waves_goda(opt, out), std::invalid_argument);
}

}  // namespace
}  // namespace swell::waves
