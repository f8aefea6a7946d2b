// Running a program (the real `swell`) in a child process for end-to-end tests: arguments,
// extra environment, a file size limit, stderr into a file.
#pragma once

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace swell::test {

struct ChildOptions {
  std::vector<std::string> env;      // "NAME=value"
  rlim_t file_size = RLIM_INFINITY;  // RLIMIT_FSIZE in bytes
  std::string err;                   // stderr into this file (default: discarded)
};

// Starts argv[0] with `argv`; stdout is discarded.
inline pid_t spawn(const std::vector<std::string>& args, const ChildOptions& o = {}) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<std::string> all = args;
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    for (const auto& e : o.env) putenv(const_cast<char*>(e.c_str()));
    const int devnull = ::open("/dev/null", O_WRONLY);
    const int errfd =
        o.err.empty() ? devnull : ::open(o.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(devnull, 1);
    dup2(errfd, 2);
    if (o.file_size != RLIM_INFINITY) {
      const rlimit lim{o.file_size, o.file_size};
      setrlimit(RLIMIT_FSIZE, &lim);
    }
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

// The exit code, or minus the signal that ended the child.
inline int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

}  // namespace swell::test
