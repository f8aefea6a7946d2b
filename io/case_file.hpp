// Reading a YAML case file into a validated CaseSpec.
//
// Every problem found in a case file (missing file, YAML syntax, unknown or missing keys, wrong
// types, invalid values) is reported by throwing CaseError, whose message reads
//   <file>:<line>: <key path>: <what is wrong and what was expected>
// so that a user can go straight to the offending line. Key paths are written as in the file,
// with list items indexed from 0: `physics.viscosity.alpha`, `bodies[1].shape.box.min`.
#pragma once

#include <stdexcept>
#include <string>

#include "io/case_spec.hpp"

namespace swell {

// An error in a case file. what() is "<file>:<line>: <message>", or "<file>: <message>" when
// no line applies (the file could not be read).
class CaseError : public std::runtime_error {
 public:
  CaseError(const std::string& file, int line, const std::string& message);

  const std::string& file() const noexcept { return file_; }
  int line() const noexcept { return line_; }  // 1-based; 0 when no line applies
  const std::string& message() const noexcept { return message_; }  // without "<file>:<line>: "

 private:
  std::string file_;
  int line_;
  std::string message_;
};

// Reads and parses the case file at `path`. CaseSpec::file is `path`, CaseSpec::text the file's
// content. Throws CaseError.
CaseSpec load_case_file(const std::string& path);

// Parses case file content held in memory. `file_label` names it in error messages, is stored
// in CaseSpec::file, and its stem is the default case name. Throws CaseError.
CaseSpec parse_case_text(const std::string& text, const std::string& file_label);

}  // namespace swell
