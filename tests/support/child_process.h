// A `camsim ARGS` child process for tests that signal, time or kill the real binary
// (CAMSIM_BINARY): stdout and stderr go to files next to the outputs.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/text_file.h"

extern char** environ;

namespace camsim {
namespace test {

// `camsim ARGS` as a child process, stdout and stderr into files next to the outputs.
class Child {
 public:
  Child(const std::vector<std::string>& args, const std::filesystem::path& logPrefix)
      : errPath_(logPrefix.string() + ".stderr") {
    std::vector<std::string> argv = {CAMSIM_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (auto& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string out = logPrefix.string() + ".stdout";
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, errPath_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    if (::posix_spawn(&pid_, cargv[0], &actions, nullptr, cargv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
    start_ = std::chrono::steady_clock::now();
  }
  ~Child() {
    if (pid_ > 0 && !status_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  pid_t pid() const { return pid_; }
  bool running() const { return pid_ > 0 && !status_; }
  void signal(int sig) const { ::kill(pid_, sig); }
  // Waits at most `limit`; the raw wait status, or none on a timeout.
  std::optional<int> wait(std::chrono::duration<double> limit) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!status_) {
      int status = 0;
      const pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_)
        status_ = status;
      else if (r < 0 || std::chrono::steady_clock::now() > deadline)
        break;
      else
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return status_;
  }
  // Lets the child work until it has used `cpu` seconds of CPU or `limit` seconds have passed
  // since it started; whether it is still running then (it must not have exited, e.g. before
  // a test signals it mid-way).
  bool workFor(double cpu, double limit) {
    while (cpuSeconds() < cpu && secondsSinceStart() < limit) {
      if (wait(std::chrono::seconds(0))) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return !wait(std::chrono::seconds(0));
  }
  double secondsSinceStart() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  // CPU seconds the child has used (utime + stime from /proc), 0 if unknown.
  double cpuSeconds() const {
    std::istringstream stat(test::readFile("/proc/" + std::to_string(pid_) + "/stat"));
    std::string field;
    const auto close = stat.str().rfind(')');  // the command name may hold spaces
    if (close == std::string::npos) return 0.0;
    stat.seekg(static_cast<std::streamoff>(close + 2));
    std::vector<std::string> fields;
    while (stat >> field) fields.push_back(field);
    if (fields.size() < 13) return 0.0;  // fields[11], [12]: utime, stime (fields 14, 15)
    return static_cast<double>(std::stoll(fields[11]) + std::stoll(fields[12])) /
           static_cast<double>(::sysconf(_SC_CLK_TCK));
  }
  std::string err() const { return test::readFile(errPath_); }

 private:
  pid_t pid_ = -1;
  std::string errPath_;
  std::optional<int> status_;
  std::chrono::steady_clock::time_point start_;
};

inline int exitCode(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

}  // namespace test
}  // namespace camsim
