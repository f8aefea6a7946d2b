#include "apps/subcommand.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>

namespace swell {

bool Subcommand::chosen() const {
  return app_->parsed();
}

std::string Subcommand::name() const {
  return app_->get_name();
}

const CLI::Validator& count_check() {
  static const CLI::Validator v(
      [](std::string& s) -> std::string {
        char* end = nullptr;
        const long n = std::strtol(s.c_str(), &end, 10);
        if (s.empty() || *end != '\0' || n < 1)
          return "expected a whole number >= 1, got '" + s + "'";
        return {};
      },
      "N>=1");
  return v;
}

const CLI::Validator& positive_check() {
  static const CLI::Validator v(
      [](std::string& s) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || !(x > 0.0) || !std::isfinite(x))
          return "expected a number > 0, got '" + s + "'";
        return {};
      },
      "X>0");
  return v;
}

void add_set_option(CLI::App* cmd, std::vector<std::string>& sets) {
  cmd->add_option("--set", sets,
                  "edit the case: key.path=value (YAML value; repeatable), e.g. "
                  "--set physics.boundary.model=mdbc --set bodies.2.boundary=dbc")
      ->allow_extra_args(false);
}

}  // namespace swell
