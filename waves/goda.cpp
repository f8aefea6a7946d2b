#include "waves/goda.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace swell::waves {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void require(bool ok, const char* name, const char* expected, double v) {
  if (!ok || std::isnan(v))
    throw std::invalid_argument(std::string("goda: ") + name + ": expected " + expected + ", got " +
                                num(v));
}

}  // namespace

double GodaPressure::pressure(double z) const {
  const double h_base = input.base_depth;
  if (z < -h_base || z > hc_star) return 0.0;
  if (z <= 0.0) return p1 + (p1 - p2) * z / input.depth;  // p1 at the SWL, p2 at z = -h
  return p1 * (1.0 - z / eta_star);                       // to zero at eta*
}

GodaPressure goda_pressure(const GodaInput& raw) {
  GodaInput in = raw;
  if (std::isnan(in.base_depth)) in.base_depth = in.depth;
  if (std::isnan(in.berm_depth)) in.berm_depth = in.base_depth;
  if (std::isnan(in.breaking_depth)) in.breaking_depth = in.depth;
  const auto finite_positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  require(finite_positive(in.height), "H (wave height)", "a number > 0 [m]", in.height);
  require(finite_positive(in.period), "T (period)", "a number > 0 [s]", in.period);
  require(finite_positive(in.depth), "h (depth)", "a number > 0 [m]", in.depth);
  require(finite_positive(in.base_depth) && in.base_depth <= in.depth,
          "h' (depth of the caisson base)", "0 < h' <= h", in.base_depth);
  require(finite_positive(in.berm_depth) && in.berm_depth <= in.base_depth,
          "d (depth above the berm)", "0 < d <= h'", in.berm_depth);
  require(finite_positive(in.breaking_depth) && in.breaking_depth >= in.berm_depth,
          "h_b (depth 5 H1/3 seaward)", "h_b >= d [m]", in.breaking_depth);
  require(in.freeboard >= 0.0, "h_c (crest freeboard)", "a number >= 0 [m]", in.freeboard);
  require(std::abs(in.beta_deg) < 90.0, "beta (obliquity)", "|beta| < 90 [deg]", in.beta_deg);
  for (const double l : {in.lambda1, in.lambda2, in.lambda3})
    require(l >= 0.0 && std::isfinite(l), "lambda", "a modification factor >= 0", l);
  require(in.width >= 0.0 && std::isfinite(in.width), "B (caisson width)", "a number >= 0 [m]",
          in.width);
  require(finite_positive(in.rho), "rho", "a density > 0 [kg/m^3]", in.rho);
  require(finite_positive(in.g), "g", "gravity > 0 [m/s^2]", in.g);

  GodaPressure r;
  r.input = in;
  const double H = in.height, h = in.depth, hp = in.base_depth, d = in.berm_depth;
  const double hb = in.breaking_depth;
  const double k = wave_number(2.0 * std::numbers::pi / in.period, h, in.g);
  r.length = 2.0 * std::numbers::pi / k;
  r.kh = k * h;
  const double cb = std::cos(in.beta_deg * std::numbers::pi / 180.0);

  const double x = 2.0 * r.kh;  // 4 pi h / L
  const double ratio = x / std::sinh(x);
  r.alpha1 = 0.6 + 0.5 * ratio * ratio;
  r.alpha2 = std::min((hb - d) / (3.0 * hb) * (H / d) * (H / d), 2.0 * d / H);
  r.alpha3 = 1.0 - hp / h * (1.0 - 1.0 / std::cosh(r.kh));

  r.eta_star = 0.75 * (1.0 + cb) * in.lambda1 * H;
  r.hc_star = std::min(r.eta_star, in.freeboard);
  r.alpha4 = 1.0 - r.hc_star / r.eta_star;
  const double rgh = in.rho * in.g * H;
  r.p1 = 0.5 * (1.0 + cb) * (in.lambda1 * r.alpha1 + in.lambda2 * r.alpha2 * cb * cb) * rgh;
  r.p2 = r.p1 / std::cosh(r.kh);
  r.p3 = r.alpha3 * r.p1;
  r.p4 = r.alpha4 * r.p1;
  r.pu = 0.5 * (1.0 + cb) * r.alpha1 * r.alpha3 * in.lambda3 * rgh;

  // Trapezoids p3 -> p1 over h' and p1 -> p4 over hc*; moments about the base.
  const double hc = r.hc_star;
  r.force = 0.5 * (r.p1 + r.p3) * hp + 0.5 * (r.p1 + r.p4) * hc;
  r.moment = (2.0 * r.p1 + r.p3) * hp * hp / 6.0 + 0.5 * (r.p1 + r.p4) * hp * hc +
             (r.p1 + 2.0 * r.p4) * hc * hc / 6.0;
  r.uplift_force = 0.5 * r.pu * in.width;
  r.uplift_moment = 2.0 / 3.0 * r.uplift_force * in.width;
  return r;
}

}  // namespace swell::waves
