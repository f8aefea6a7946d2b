// SIGINT and SIGTERM during `swell run`: the first asks the run loop to stop cleanly (write a
// checkpoint and flush the outputs between two steps, then leave with Interrupted); a second
// one ends the process at once (exit 128 + signal), the files on disk being crash-safe.
#pragma once

#include <stdexcept>
#include <string>

namespace swell {

// Installs the handlers (process-wide; call once, from main).
void install_stop_handlers();

// The signal received (SIGINT or SIGTERM), or 0. One load; safe to call every step.
int stop_requested();

// Thrown by the run loop after it stopped on a signal; the message says where it stopped and
// how to continue. The process should exit with exit_code() (130 SIGINT, 143 SIGTERM).
class Interrupted : public std::runtime_error {
 public:
  Interrupted(int signal, const std::string& message)
      : std::runtime_error(message), signal_(signal) {}
  int signal() const { return signal_; }
  int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

}  // namespace swell
