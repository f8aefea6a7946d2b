#include "case/identity.hpp"

#include <openssl/evp.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

namespace swell {
namespace {

// Incremental SHA-256 through OpenSSL's EVP interface.
class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1)
      throw std::runtime_error("case identity: cannot start a SHA-256 digest (OpenSSL)");
  }
  void add(const void* data, std::size_t n) {
    if (EVP_DigestUpdate(ctx_.get(), data, n) != 1)
      throw std::runtime_error("case identity: SHA-256 update failed (OpenSSL)");
  }
  // A length-prefixed field, so that field boundaries are part of what is hashed.
  void field(char tag, const std::string& s) {
    const std::uint64_t n = s.size();
    add(&tag, 1);
    add(&n, sizeof n);
    add(s.data(), s.size());
  }
  std::string hex() {
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    if (EVP_DigestFinal_ex(ctx_.get(), md, &len) != 1)
      throw std::runtime_error("case identity: SHA-256 final failed (OpenSSL)");
    static const char digits[] = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < len; ++i) {
      out += digits[md[i] >> 4];
      out += digits[md[i] & 15];
    }
    return out;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx_;
};

struct Walker {
  Sha256& sha;
  std::filesystem::path base;

  void file_bytes(const std::string& name) {
    const std::filesystem::path p = base / name;  // an absolute name replaces base
    std::ifstream in(p, std::ios::binary);
    if (!in) {
      sha.field('m', name);  // missing: the set-up will say so
      return;
    }
    sha.field('f', name);
    char buf[1 << 16];
    while (in.read(buf, sizeof buf) || in.gcount() > 0) {
      sha.add(buf, static_cast<std::size_t>(in.gcount()));
      if (!in) break;
    }
  }

  void node(const YAML::Node& n, const std::string& path) {
    switch (n.Type()) {
      case YAML::NodeType::Scalar:
        sha.field('s', n.Scalar());
        break;
      case YAML::NodeType::Sequence:
        sha.field('[', std::to_string(n.size()));
        for (const auto& item : n) node(item, path + "[]");
        break;
      case YAML::NodeType::Map:
        sha.field('{', std::to_string(n.size()));
        for (const auto& kv : n) {
          const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string();
          const std::string child = path.empty() ? key : path + "." + key;
          if (child == "time.end") continue;  // may change on restart
          node(kv.first, path);
          node(kv.second, child);
          if (key == "file" && kv.second.IsScalar()) file_bytes(kv.second.Scalar());
        }
        break;
      default:
        sha.field('~', "");
        break;
    }
  }
};

}  // namespace

std::string case_identity(const CaseSpec& spec) {
  Sha256 sha;
  sha.field('n', spec.name);
  sha.field('d', std::to_string(spec.dim));
  Walker w{sha, std::filesystem::path(spec.file).parent_path()};
  try {
    w.node(YAML::Load(spec.text), "");
  } catch (const YAML::Exception&) {
    sha.field('t', spec.text);  // not YAML (a hand-made spec in a test): the text itself
  }
  return sha.hex();
}

}  // namespace swell
