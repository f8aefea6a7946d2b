#include "apps/goda_command.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "io/provenance.hpp"
#include "io/vtk_writer.hpp"

namespace swell {
namespace {

std::string line(const char* label, const char* unit, double v) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "  %-44s %.6g%s%s\n", label, v, *unit ? " " : "", unit);
  return buf;
}

// "l1,l2,l3" -> the three modification factors.
void parse_lambda(const std::string& text, waves::GodaInput& in) {
  double* v[3] = {&in.lambda1, &in.lambda2, &in.lambda3};
  std::stringstream s(text);
  std::string item;
  int n = 0;
  for (; std::getline(s, item, ','); ++n) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (n >= 3 || item.empty() || *end != '\0' || !std::isfinite(x))
      throw std::invalid_argument("--lambda: expected three numbers l1,l2,l3, got '" + text + "'");
    *v[n] = x;
  }
  if (n != 3)
    throw std::invalid_argument("--lambda: expected three numbers l1,l2,l3, got '" + text + "'");
}

// Heights of the table: the base, the SWL, the top (hc*) and evenly spaced points between,
// so that linear interpolation of the table is the distribution exactly.
std::vector<double> table_heights(const waves::GodaPressure& r) {
  std::vector<double> z;
  const int below = 30, above = 10;
  for (int i = 0; i <= below; ++i) z.push_back(-r.input.base_depth * (1.0 - double(i) / below));
  for (int i = 1; i <= above; ++i) z.push_back(r.hc_star * double(i) / above);
  return z;
}

}  // namespace

void run_waves_goda(const WavesGodaOptions& opt, std::ostream& out) {
  if (!opt.csv.empty()) require_output_folder(opt.csv, "--csv");
  waves::GodaInput in = opt.input;
  in.beta_deg = opt.beta;
  if (!opt.lambda.empty()) parse_lambda(opt.lambda, in);
  const waves::GodaPressure r = waves::goda_pressure(in);
  const waves::GodaInput& q = r.input;

  std::ostringstream rep;
  rep << "Goda (1974, 2000) wave pressure on a vertical wall: H = " << q.height
      << " m, T = " << q.period << " s, h = " << q.depth << " m, h' = " << q.base_depth
      << " m, d = " << q.berm_depth << " m, h_b = " << q.breaking_depth
      << " m, h_c = " << q.freeboard << " m, beta = " << q.beta_deg
      << " deg, lambda = " << q.lambda1 << ", " << q.lambda2 << ", " << q.lambda3
      << " (rho = " << q.rho << " kg/m^3, g = " << q.g << " m/s^2)\n";
  rep << line("wave length L at h", "m", r.length) << line("kh", "", r.kh)
      << line("eta* (top of the pressure, above SWL)", "m", r.eta_star)
      << line("hc* = min(eta*, h_c)", "m", r.hc_star) << line("alpha1", "", r.alpha1)
      << line("alpha2", "", r.alpha2) << line("alpha3", "", r.alpha3)
      << line("alpha4", "", r.alpha4) << line("p1 (at the SWL)", "Pa", r.p1)
      << line("p2 (at the sea bed, z = -h)", "Pa", r.p2)
      << line("p3 (at the caisson base, z = -h')", "Pa", r.p3)
      << line("p4 (at the crest, z = hc*)", "Pa", r.p4)
      << line("pu (uplift at the seaward toe)", "Pa", r.pu)
      << line("horizontal force P per metre", "N/m", r.force)
      << line("its moment about the base M_P", "N m/m", r.moment)
      << line("lever arm M_P / P above the base", "m", r.moment / r.force);
  if (q.width > 0.0)
    rep << line("uplift U = pu B / 2", "N/m", r.uplift_force)
        << line("its moment about the heel M_U", "N m/m", r.uplift_moment);
  rep << "wave pressure on the face (below the SWL: in excess of hydrostatic):\n"
      << "     z [m]      p [Pa]\n";
  const double corners[] = {-q.base_depth, -q.base_depth / 2, 0.0, r.hc_star / 2, r.hc_star};
  for (const double z : corners) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "  %8.4g  %10.5g\n", z, r.pressure(z));
    rep << buf;
  }

  if (!opt.csv.empty()) {
    std::ostringstream csv;
    char buf[64];
    csv << "# swell waves goda: Goda (1974, 2000) wave pressure on a vertical wall\n"
        << provenance_text(capture_provenance(), "# ");
    auto meta = [&](const char* key, double v) {
      std::snprintf(buf, sizeof buf, "%.9g", v);
      csv << "# " << key << ": " << buf << "\n";
    };
    meta("H [m]", q.height), meta("T [s]", q.period), meta("h [m]", q.depth);
    meta("h' [m]", q.base_depth), meta("d [m]", q.berm_depth), meta("h_c [m]", q.freeboard);
    meta("beta [deg]", q.beta_deg), meta("L [m]", r.length), meta("eta* [m]", r.eta_star);
    meta("hc* [m]", r.hc_star), meta("alpha1", r.alpha1), meta("alpha2", r.alpha2);
    meta("alpha3", r.alpha3), meta("p1 [Pa]", r.p1), meta("p2 [Pa]", r.p2);
    meta("p3 [Pa]", r.p3), meta("p4 [Pa]", r.p4), meta("pu [Pa]", r.pu);
    meta("force [N/m]", r.force), meta("moment [N m/m]", r.moment);
    meta("uplift force [N/m]", r.uplift_force);
    csv << "z [m],p [Pa]\n";
    for (const double z : table_heights(r)) {
      std::snprintf(buf, sizeof buf, "%.9g,%.9g\n", z, r.pressure(z));
      csv << buf;
    }
    write_file_atomically(opt.csv, csv.str());
    rep << "distribution written to " << opt.csv << "\n";
  }
  out << rep.str();
}

Subcommand add_waves_goda_command(CLI::App& waves) {
  auto opt = std::make_shared<WavesGodaOptions>();
  waves::GodaInput& in = opt->input;
  auto* a = waves.add_subcommand(
      "goda",
      "Goda's wave pressures and force on a vertical wall or caisson (swell waves goda H T h)");
  a->add_option("H", in.height, "wave height [m] (H_max for design)")->required();
  a->add_option("T", in.period, "wave period [s]")->required();
  a->add_option("h", in.depth, "water depth in front of the structure [m]")->required();
  a->add_option("--h-prime", in.base_depth, "depth of the caisson base below SWL [m] (default h)");
  a->add_option("--d", in.berm_depth, "depth above the armour/berm crown [m] (default h')");
  a->add_option("--hb", in.breaking_depth, "depth 5 H1/3 seaward of the wall [m] (default h)");
  a->add_option("--hc", in.freeboard, "crest freeboard above SWL [m] (default: above eta*)");
  a->add_option("--beta", opt->beta, "angle between wave direction and wall normal [deg]");
  a->add_option("--lambda", opt->lambda, "modification factors l1,l2,l3 (default 1,1,1)");
  a->add_option("--width", in.width, "caisson width B for the uplift force [m]");
  a->add_option("--rho", in.rho, "water density [kg/m^3] (default 1000)");
  a->add_option("-g", in.g, "gravity [m/s^2] (default 9.81)");
  a->add_option("--csv", opt->csv, "write the distribution z, p(z) and the results as CSV");
  return Subcommand(a, [opt] {
    run_waves_goda(*opt, std::cout);
    return 0;
  });
}

}  // namespace swell
