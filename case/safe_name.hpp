// Case names become file names (OUTDIR/<name>.h5, vtk/<name>_0001.vtp, out/<name>): they are
// restricted to a portable set that cannot leave the output folder or name a hidden file.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace swell {

constexpr std::size_t kMaxNameLength = 100;

// What a valid name looks like, for error messages.
inline const char* safe_name_rule() {
  return "1 to 100 characters from A-Z a-z 0-9 . _ -, not starting with '.'";
}

inline bool is_safe_name_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
         c == '_' || c == '-';
}

inline bool is_safe_name(std::string_view name) {
  if (name.empty() || name.size() > kMaxNameLength || name.front() == '.') return false;
  for (const char c : name)
    if (!is_safe_name_char(c)) return false;
  return true;
}

// A safe name made from any text (the case file's name when the case sets none): every other
// character becomes '_', a leading '.' too, cut to the maximum length; "case" if empty.
inline std::string make_safe_name(std::string_view text) {
  std::string out;
  for (const char c : text.substr(0, kMaxNameLength)) out += is_safe_name_char(c) ? c : '_';
  if (!out.empty() && out.front() == '.') out.front() = '_';
  return out.empty() ? "case" : out;
}

}  // namespace swell
