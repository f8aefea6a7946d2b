// Running a program (the real `swell`) in a child process for end-to-end tests: arguments,
// extra or removed environment, a working directory, a file size limit, stdout and stderr into
// files.
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
  std::string out;                   // stdout into this file (default: discarded)
  std::string cwd;                   // working directory (default: the parent's)
  std::vector<std::string> unset;    // environment variables to remove
};

// Starts argv[0] with `argv`; stdout is discarded unless `o.out` names a file.
inline pid_t spawn(const std::vector<std::string>& args, const ChildOptions& o = {}) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<std::string> all = args;
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    for (const auto& e : o.env) putenv(const_cast<char*>(e.c_str()));
    for (const auto& e : o.unset) unsetenv(e.c_str());
    if (!o.cwd.empty() && chdir(o.cwd.c_str()) != 0) _exit(126);
    const int devnull = ::open("/dev/null", O_WRONLY);
    const int errfd =
        o.err.empty() ? devnull : ::open(o.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int outfd =
        o.out.empty() ? devnull : ::open(o.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(outfd, 1);
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
