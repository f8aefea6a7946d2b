// A `swell` subcommand registered by its own file: the CLI11 app it added (its options bound
// to options the closure owns) and what running it does. A command file offers
// `Subcommand add_<name>_command(CLI::App& parent)`; apps/swell.cpp keeps the returned objects
// and runs the one that was chosen.
#pragma once

#include <functional>
#include <iosfwd>
#include <utility>

namespace CLI {
class App;
}

namespace swell {

class Subcommand {
 public:
  Subcommand(CLI::App* app, std::function<void(std::ostream&)> run)
      : app_(app), run_(std::move(run)) {}
  // Whether it was named on the command line.
  bool chosen() const;
  void run(std::ostream& out) const { run_(out); }

 private:
  CLI::App* app_;
  std::function<void(std::ostream&)> run_;
};

}  // namespace swell
