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
#include <vector>

#include "case/spec.hpp"

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

// Reads the case file at `path` with command-line edits applied (`swell run --set`, as
// DualSPHysics' command-line options and OpenFOAM's foamDictionary -set): each edit is
// `key.path=value`, the path written as in the file with list items by index (`bodies.2.boundary`,
// `physics.shifting.model`), the value YAML (`mdbc`, `{model: fickian, coefficient: 1}`,
// `[0, -9.81]`). Missing maps on the path are created; the index one past a list's last item
// appends an item (`gauges.4={name: S1, kind: pressure, ...}` on a list of 4 gauges); the edited
// tree is then read by the ordinary reader, so every edit is checked like a hand-written key (line
// numbers in its messages then refer to the edited text, as for `swell validate`'s edits).
// CaseSpec::text is the edited text, so a checkpoint's case identity includes the edits. A
// malformed edit is a CaseError naming the edit. No edits: load_case_file(path).
CaseSpec load_case_file(const std::string& path, const std::vector<std::string>& sets);

// Applies `sets` (as above) to case-file YAML text and returns the edited text (emitted by
// yaml-cpp: comments are dropped). `file_label` names the case in errors. Throws CaseError.
std::string edit_case_text(const std::string& text, const std::vector<std::string>& sets,
                           const std::string& file_label);

// Parses case file content held in memory. `file_label` names it in error messages, is stored
// in CaseSpec::file, and its stem is the default case name. Throws CaseError.
CaseSpec parse_case_text(const std::string& text, const std::string& file_label);

}  // namespace swell
