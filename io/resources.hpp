// Swell's shared files (cases/, validation/ manifests, reference data, committed results and
// plot scripts, bench/ cases): where a command finds them at run time, in a source checkout,
// a build tree or an installed prefix (`cmake --install`, share/swell/).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace swell {

// One place Swell's shared files may be, and why it is searched.
struct DataRoot {
  std::filesystem::path dir;
  std::string origin;  // "SWELL_HOME", "install prefix" or "source tree"
};

// The places searched, in order: $SWELL_HOME when it is set and not empty (then ONLY it: a
// mistyped SWELL_HOME is an error, never silently replaced by another tree); else the
// installed share/swell relative to the running executable (/proc/self/exe, so a moved prefix
// still works), then the source tree the executable was built from (a build-tree run).
std::vector<DataRoot> data_roots();

// share/swell of the prefix the running executable is installed in (whether or not it
// exists); empty when /proc/self/exe cannot be read.
std::filesystem::path installed_data_dir();

// `relative` (e.g. "validation/martin_moyce/validation.yaml") under the first root that has
// it; `tried` (if given) receives every path looked at.
std::optional<std::filesystem::path> find_data_file(const std::string& relative,
                                                    std::vector<std::string>* tried = nullptr);

// The same, or std::invalid_argument (exit 2): "<what>: not found (tried A, B, C); ..."
std::filesystem::path require_data_file(const std::string& relative, const std::string& what);

// "A (SWELL_HOME), B, ..." for error messages.
std::string tried_list(const std::vector<std::string>& tried);

// What to do when a file was not found: set SWELL_HOME, or (when it is set) fix or unset it.
std::string data_roots_hint();

// Whether `path` lies inside `dir` (both made absolute and normalised lexically).
bool path_within(const std::filesystem::path& path, const std::filesystem::path& dir);

}  // namespace swell
