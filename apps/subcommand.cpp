#include "apps/subcommand.hpp"

#include <CLI/CLI.hpp>

namespace swell {

bool Subcommand::chosen() const {
  return app_->parsed();
}

}  // namespace swell
