// The log of a `swell run`: everything the run prints (header, warnings, summary) goes to the
// console stream, flushed at every line, and to OUTDIR/run.log, which also gets the progress
// lines and the error that ended a run. The file is opened only once the run's set-up has
// worked (a refused run leaves no log); what was printed before is written to it then.
#pragma once

#include <cstdio>
#include <filesystem>
#include <ostream>
#include <streambuf>
#include <string>

namespace swell {

class RunLog : public std::ostream {
 public:
  explicit RunLog(std::ostream& console);
  ~RunLog() override;
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;

  // Opens `file` (appending on a restart), writes what was logged so far; from then on every
  // line reaches the file when it ends. Throws std::runtime_error if it cannot be opened.
  void attach(const std::filesystem::path& file, bool append);
  bool attached() const { return buf_.file != nullptr; }
  // One line for the file only (progress, the final error); no allocation once attached.
  void file_line(const char* text);

 private:
  struct Buf : std::streambuf {
    std::ostream* console = nullptr;
    std::FILE* file = nullptr;
    std::string pending;  // logged before the file was attached
    int overflow(int c) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;
    int sync() override;
    void to_file(const char* s, std::size_t n);
  };
  Buf buf_;
};

}  // namespace swell
