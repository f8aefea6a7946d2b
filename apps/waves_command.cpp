#include "apps/waves_command.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "apps/goda_command.hpp"
#include "apps/wave_analysis_command.hpp"
#include "apps/wave_predict_command.hpp"
#include "apps/wave_target_command.hpp"
#include "waves/theory.hpp"

namespace swell {

namespace {

std::string line(const char* label, const char* format, double v) {
  char value[64];
  std::snprintf(value, sizeof value, format, v);
  char buf[160];
  std::snprintf(buf, sizeof buf, "  %-34s %s\n", label, value);
  return buf;
}

}  // namespace

int run_waves(const WavesOptions& opt, std::ostream& out) {
  waves::PaddleGeometry paddle;
  paddle.depth = opt.depth;
  if (opt.paddle == "flap") {
    paddle.type = waves::PaddleGeometry::Type::Flap;
    paddle.hinge_height = opt.hinge;
  } else if (opt.paddle != "piston") {
    throw std::invalid_argument("--paddle: expected piston or flap, got '" + opt.paddle + "'");
  }
  if (opt.order != 1 && opt.order != 2)
    throw std::invalid_argument("--order: expected 1 or 2, got " + std::to_string(opt.order));
  // As a case file's `order: 2` on a flap paddle (case/motion): refused, not just warned.
  if (opt.order == 2 && paddle.type == waves::PaddleGeometry::Type::Flap)
    throw std::invalid_argument(
        "--order 2: second-order generation is implemented for pistons only; use --order 1 "
        "with a flap");
  const waves::WaveAssessment a = waves::assess_regular_wave(opt.height, opt.period, opt.depth,
                                                             paddle, opt.order, opt.dp, opt.g);
  out << "regular wave H = " << opt.height << " m, T = " << opt.period << " s in d = " << opt.depth
      << " m (g = " << opt.g << " m/s^2)\n";
  out << line("wave length L [m]", "%.5g", a.length) << line("wave number k [rad/m]", "%.5g", a.k)
      << line("kd", "%.4g", a.kd) << line("d/L", "%.4g", a.relative_depth)
      << line("phase speed c [m/s]", "%.4g", a.celerity)
      << line("group speed cg [m/s]", "%.4g", a.group_celerity)
      << line("steepness H/L", "%.4g", a.steepness)
      << line("Ursell number H L^2/d^3", "%.4g", a.ursell)
      << line("d/(g T^2) (Le Mehaute chart)", "%.4g", a.d_gt2)
      << line("H/(g T^2) (Le Mehaute chart)", "%.4g", a.h_gt2)
      << line("Miche breaking height [m]", "%.4g", a.breaking_height)
      << line("Stokes a2/a1", "%.4g", a.harmonic_ratio);
  out << "  depth: " << a.depth_regime << "\n  theory: " << a.theory << "\n";
  out << (opt.paddle == "flap" ? "flap hinged " + std::to_string(opt.hinge) + " m above the bed"
                               : std::string("piston"))
      << ":\n"
      << line("transfer function H/S", "%.5g", a.transfer)
      << line("stroke S at the SWL [m]", "%.5g", a.stroke);
  if (paddle.type == waves::PaddleGeometry::Type::Piston)
    out << line("2nd-order (Madsen) term [m]", "%.4g", a.stroke2);
  if (opt.dp > 0.0)
    out << line("H/dp", "%.4g", opt.height / opt.dp) << line("L/dp", "%.4g", a.length / opt.dp);
  for (const auto& w : a.warnings) out << "warning: " << w << "\n";
  if (a.warnings.empty()) out << "no warnings: order " << opt.order << " generation is valid\n";
  return static_cast<int>(a.warnings.size());
}

Subcommand add_waves_command(CLI::App& app) {
  auto o = std::make_shared<WavesOptions>();
  auto* waves = app.add_subcommand(
      "waves",
      "wave theory (swell waves H T d [--paddle flap --hinge l]), analysis (analyse), Goda's wall "
      "pressures (goda), a case's target wave (target)");
  waves->require_subcommand(0, 1);
  // `swell waves analyse | predict | goda | target`: each file registers its own.
  auto subcommands = std::make_shared<const std::vector<Subcommand>>(
      std::vector<Subcommand>{add_waves_analyse_command(*waves), add_waves_predict_command(*waves),
                              add_waves_goda_command(*waves), add_waves_target_command(*waves)});
  auto* height = waves->add_option("H", o->height, "wave height [m]")->check(positive_check());
  waves->add_option("T", o->period, "wave period [s]")->check(positive_check());
  waves->add_option("d", o->depth, "still-water depth [m]")->check(positive_check());
  waves->add_option("--paddle", o->paddle, "piston (default) | flap")
      ->check(CLI::IsMember({"piston", "flap"}));
  waves->add_option("--hinge", o->hinge, "flap: hinge height above the bed [m] (< 0: below)");
  waves->add_option("--order", o->order, "generation order 1 | 2 (default 1)")
      ->check(CLI::IsMember({1, 2}));
  waves->add_option("--dp", o->dp, "particle spacing [m]: resolution checks")
      ->check(positive_check());
  waves->add_option("-g", o->g, "gravity [m/s^2] (default 9.81)")->check(positive_check());
  return Subcommand(waves, [o, subcommands, height] {
    for (const Subcommand& c : *subcommands)
      if (c.chosen()) return c.run();
    if (height->count() == 0 || o->period <= 0.0 || o->depth <= 0.0)
      throw std::invalid_argument("waves: expected H T d (height [m], period [s], depth [m])");
    run_waves(*o, std::cout);
    return 0;
  });
}

}  // namespace swell
