// What identifies a case for `swell run --restart`: a SHA-256 over the case's content and the
// bytes of every file it reads (meshes, motion series), stored in each checkpoint. A restart
// whose case differs is refused, so a folder's checkpoint is never continued by another case.
#pragma once

#include <string>

#include "case/spec.hpp"

namespace swell {

// Hex SHA-256 of: the case name, the parsed YAML tree of spec.text without `time.end` (so a
// restart may extend a run; comments and layout do not count), and the bytes of each file
// named by a `file:` key, resolved against the case file's folder, in document order. A file
// that cannot be read counts by its name only (the case set-up reports it).
std::string case_identity(const CaseSpec& spec);

}  // namespace swell
