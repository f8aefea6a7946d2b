#include "run/run_log.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace swell {

RunLog::RunLog(std::ostream& console) : std::ostream(nullptr) {
  buf_.console = &console;
  rdbuf(&buf_);
}

RunLog::~RunLog() {
  if (buf_.file) std::fclose(buf_.file);
}

void RunLog::attach(const std::filesystem::path& file, bool append) {
  if (buf_.file) return;
  std::FILE* f = std::fopen(file.c_str(), append ? "a" : "w");
  if (!f)
    throw std::runtime_error(file.string() + ": cannot open the run log (" + std::strerror(errno) +
                             ")");
  buf_.file = f;
  if (!buf_.pending.empty()) buf_.to_file(buf_.pending.data(), buf_.pending.size());
  buf_.pending.clear();
  buf_.pending.shrink_to_fit();
  std::fflush(f);
}

void RunLog::file_line(const char* text) {
  const std::size_t n = std::strlen(text);
  buf_.to_file(text, n);
  if (n == 0 || text[n - 1] != '\n') buf_.to_file("\n", 1);
  if (buf_.file) std::fflush(buf_.file);
}

void RunLog::Buf::to_file(const char* s, std::size_t n) {
  if (file)
    std::fwrite(s, 1, n, file);  // a failed log write never stops a run
  else
    pending.append(s, n);
}

// Unbuffered: every character goes straight through; a newline flushes both streams, so a run
// killed (SIGKILL) with its output redirected keeps every line printed before.
int RunLog::Buf::overflow(int c) {
  if (c == traits_type::eof()) return traits_type::not_eof(c);
  const char ch = traits_type::to_char_type(c);
  return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
}

std::streamsize RunLog::Buf::xsputn(const char* s, std::streamsize n) {
  console->write(s, n);
  to_file(s, static_cast<std::size_t>(n));
  if (std::memchr(s, '\n', static_cast<std::size_t>(n))) sync();
  return n;
}

int RunLog::Buf::sync() {
  console->flush();
  if (file) std::fflush(file);
  return 0;
}

}  // namespace swell
