// A `swell` command registered by its own file: the CLI11 app it added (its options bound to
// options its closure owns) and what running it does, returning the exit code. Each command
// file offers `Subcommand add_<name>_command(CLI::App& parent)`; apps/swell.cpp keeps the list
// and runs the one that was chosen. Errors are thrown, not printed: main turns them into exit
// codes. The option checks and options several commands share are here too.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace swell {

class Subcommand {
 public:
  Subcommand(CLI::App* app, std::function<int()> run) : app_(app), run_(std::move(run)) {}
  // Whether it was named on the command line.
  bool chosen() const;
  std::string name() const;
  // Runs it; returns the process's exit code.
  int run() const { return run_(); }

 private:
  CLI::App* app_;
  std::function<int()> run_;
};

// Option checks with short messages (CLI::PositiveNumber prints the whole double range).
const CLI::Validator& count_check();     // a whole number >= 1
const CLI::Validator& positive_check();  // a finite number > 0

// `--set key.path=value`, repeatable, one edit per occurrence (case/reader.hpp).
void add_set_option(CLI::App* cmd, std::vector<std::string>& sets);

}  // namespace swell
