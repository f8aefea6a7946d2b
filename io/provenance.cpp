#include "io/provenance.hpp"

#include <omp.h>
#include <unistd.h>

#include <array>
#include <ctime>
#include <fstream>
#include <sstream>

#include "swell/git_commit.hpp"
#include "swell/version.hpp"

namespace swell {
namespace {

std::string quote_arg(const std::string& a) {
  if (!a.empty() && a.find_first_of(" \t\n'\"\\$`*?[]{}()<>|&;#~!") == std::string::npos) return a;
  std::string out = "'";
  for (const char c : a) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string v = line.substr(colon + 1);
    const auto b = v.find_first_not_of(" \t");
    return b == std::string::npos ? "unknown" : v.substr(b);
  }
  return "unknown";
}

}  // namespace

std::vector<std::pair<std::string, std::string>> Provenance::fields() const {
  std::vector<std::pair<std::string, std::string>> f = {{"version", version},
                                                        {"commit", commit},
                                                        {"compiler", compiler},
                                                        {"build", build},
                                                        {"command", command},
                                                        {"threads", std::to_string(threads)},
                                                        {"ranks", std::to_string(ranks)},
                                                        {"date", date},
                                                        {"host", host},
                                                        {"cpu", cpu}};
  if (!recovered.empty()) f.emplace_back("recovered", recovered);
  return f;
}

std::string quoted_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string process_command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (all.empty()) return "unknown";
  std::string out;
  std::size_t start = 0;
  while (start < all.size()) {
    std::size_t end = all.find('\0', start);
    if (end == std::string::npos) end = all.size();
    out += (out.empty() ? "" : " ") + quote_arg(all.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

std::string version_text() {
  return std::string("swell ") + SWELL_VERSION + " (commit " + SWELL_GIT_COMMIT + "; " +
         SWELL_COMPILER + "; " + SWELL_BUILD_TYPE + ": " + SWELL_BUILD_FLAGS + ")";
}

Provenance capture_provenance() {
  Provenance p;
  p.version = SWELL_VERSION;
  p.commit = SWELL_GIT_COMMIT;
  p.compiler = SWELL_COMPILER;
  p.build = std::string(SWELL_BUILD_TYPE) + ": " + SWELL_BUILD_FLAGS;
  p.command = process_command_line();
  p.threads = omp_get_max_threads();
  p.ranks = 1;
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  p.date = buf;
  std::array<char, 256> host{};
  p.host = gethostname(host.data(), host.size() - 1) == 0 && host[0] ? host.data() : "unknown";
  p.cpu = cpu_model();
  return p;
}

std::string provenance_yaml(const Provenance& p, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::ostringstream o;
  for (const auto& [k, v] : p.fields()) {
    o << pad << k << ": ";
    if (k == "threads" || k == "ranks")
      o << v;
    else
      o << quoted_string(v);
    o << "\n";
  }
  return o.str();
}

std::string provenance_text(const Provenance& p, const std::string& prefix) {
  std::ostringstream o;
  for (const auto& [k, v] : p.fields()) {
    o << prefix << k << ":" << std::string(k.size() < 10 ? 10 - k.size() : 1, ' ') << v << "\n";
  }
  return o.str();
}

}  // namespace swell
