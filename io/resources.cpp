#include "io/resources.hpp"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <stdexcept>
#include <system_error>

namespace swell {

namespace fs = std::filesystem;

// SWELL_DATA_FROM_BIN: share/swell relative to bin/ (CMake, GNUInstallDirs); SWELL_SOURCE_DIR:
// the checkout this executable was built from.
#ifndef SWELL_DATA_FROM_BIN
#define SWELL_DATA_FROM_BIN "../share/swell"
#endif

fs::path installed_data_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || exe.empty()) return {};
  return (exe.parent_path() / SWELL_DATA_FROM_BIN).lexically_normal();
}

std::vector<DataRoot> data_roots() {
  if (const char* home = std::getenv("SWELL_HOME"); home && *home)
    return {{fs::path(home), "SWELL_HOME"}};
  std::vector<DataRoot> roots;
  if (const fs::path d = installed_data_dir(); !d.empty()) roots.push_back({d, "install prefix"});
#ifdef SWELL_SOURCE_DIR
  roots.push_back({fs::path(SWELL_SOURCE_DIR), "source tree"});
#endif
  return roots;
}

std::optional<fs::path> find_data_file(const std::string& relative,
                                       std::vector<std::string>* tried) {
  for (const auto& r : data_roots()) {
    const fs::path p = r.dir / relative;
    if (tried) tried->push_back(p.string() + " (" + r.origin + ")");
    std::error_code ec;
    if (fs::exists(p, ec)) return p;
  }
  return std::nullopt;
}

std::string tried_list(const std::vector<std::string>& tried) {
  std::string list;
  for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t;
  return list;
}

std::string data_roots_hint() {
  const char* home = std::getenv("SWELL_HOME");
  if (home && *home)
    return "SWELL_HOME is set, so no other place was searched: point it at a folder holding "
           "cases/ and validation/ (a source checkout or <prefix>/share/swell), or unset it";
  return "set SWELL_HOME to a folder holding cases/ and validation/ (a source checkout or "
         "<prefix>/share/swell)";
}

fs::path require_data_file(const std::string& relative, const std::string& what) {
  std::vector<std::string> tried;
  if (auto p = find_data_file(relative, &tried)) return *p;
  throw std::invalid_argument(what + ": " + relative + " not found (tried " + tried_list(tried) +
                              "); " + data_roots_hint());
}

bool path_within(const fs::path& path, const fs::path& dir) {
  if (dir.empty()) return false;
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
  const fs::path d = fs::weakly_canonical(fs::absolute(dir), ec);
  const auto [di, pi] = std::mismatch(d.begin(), d.end(), p.begin(), p.end());
  return di == d.end() || (di->empty() && std::next(di) == d.end());  // d's trailing separator
}

}  // namespace swell
