#include "apps/wave_target_command.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "apps/validate_command.hpp"
#include "case/reader.hpp"
#include "io/provenance.hpp"
#include "io/vtk_writer.hpp"

namespace swell {

void run_waves_target(const WavesTargetOptions& opt, std::ostream& out) {
  if (!(opt.end > 0.0)) throw std::invalid_argument("--end: expected a time > 0 [s]");
  if (!(opt.every > 0.0)) throw std::invalid_argument("--every: expected an interval > 0 [s]");
  const std::vector<double> at = parse_number_list(opt.at, "--at", true);  // 0: at the paddle
  if (!opt.csv.empty()) require_output_folder(opt.csv, "--csv");
  const CaseSpec spec = load_case_file(opt.case_file, opt.sets);
  const BodySpec* body = nullptr;
  for (const auto& b : spec.bodies)
    if (b.motion.type == MotionSpec::Type::Wave && (opt.body.empty() || b.name == opt.body)) {
      body = &b;
      break;
    }
  if (!body)
    throw std::invalid_argument(
        opt.case_file + ": " +
        (opt.body.empty() ? std::string("no body has a wave motion (motion: {type: wave})")
                          : "no body '" + opt.body + "' with a wave motion"));
  const MotionSpec& m = body->motion;
  const waves::PaddleSignal& full = *m.paddle;
  waves::PaddleSignal linear = full;  // the same signal without its bound terms
  linear.bound_second_harmonic = 0.0;
  linear.pair_components = 0;

  std::ostringstream csv;
  csv.precision(9);
  csv << "# swell waves target: " << opt.case_file << ", body " << body->name << ": "
      << m.wave_label << "\n"
      << "# eta: the target elevation (ramped as the paddle); eta_bound: its second-order bound "
         "part; x from the paddle's rest face, t on the case's clock\n"
      << provenance_text(capture_provenance(), "# ") << "time [s]";
  for (const double x : at) csv << ",eta_" << x << " [m],eta_bound_" << x << " [m]";
  csv << "\n";
  // Times i * every up to --end, never past it (a rounding margin of 1e-9 intervals keeps an
  // end that is a whole number of intervals, e.g. 10 at 0.01).
  const long n = static_cast<long>(std::floor(opt.end / opt.every + 1e-9));
  for (long i = 0; i <= n; ++i) {
    const double t = i * opt.every, tau = t - m.start;
    double ramp = tau >= 0.0 && t <= m.stop ? 1.0 : 0.0;
    if (ramp > 0.0 && m.ramp > 0.0 && tau < m.ramp) {  // the motion law's smoothstep
      const double s = tau / m.ramp;
      ramp = s * s * (3.0 - 2.0 * s);
    }
    csv << t;
    for (const double x : at) {
      const double e = ramp == 0.0 ? 0.0 : ramp * full.elevation(tau, x);
      const double l = ramp == 0.0 ? 0.0 : ramp * linear.elevation(tau, x);
      csv << "," << e << "," << e - l;
    }
    csv << "\n";
  }
  if (opt.csv.empty()) {
    out << csv.str();
  } else {
    write_file_atomically(opt.csv, csv.str());
    out << "target of " << body->name << " (" << m.wave_label << ") at " << at.size()
        << " distance(s), " << n + 1 << " times, written to " << opt.csv << "\n";
  }
}

Subcommand add_waves_target_command(CLI::App& waves) {
  auto opt = std::make_shared<WavesTargetOptions>();
  auto* a = waves.add_subcommand(
      "target", "the wave a case's wavemaker is meant to make, at distances from the paddle");
  a->add_option("case", opt->case_file, "case file (YAML)")->required();
  a->add_option("--at", opt->at, "distances from the paddle's rest face x1,x2,... [m]")->required();
  a->add_option("--end", opt->end, "last time [s]")->required();
  a->add_option("--every", opt->every, "sampling interval [s] (default 0.01)");
  a->add_option("--body", opt->body, "the wavemaker body (default: the first with a wave)");
  a->add_option("--set", opt->sets, "case edit key=value, as `swell run --set`");
  a->add_option("--csv", opt->csv, "write the CSV here (default: print it)");
  return Subcommand(a, [opt] {
    run_waves_target(*opt, std::cout);
    return 0;
  });
}

}  // namespace swell
