#include "cli/python_script.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>

namespace camsim {
namespace {

// Runs argv (no shell) and waits; the exit status, or -1 if it could not run or was killed.
int runProcess(const std::vector<std::string>& argv, bool quiet) {
  std::vector<char*> cargv;
  for (const std::string& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  }
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, cargv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::optional<std::string> pythonWithMatplotlib() {
  const char* env = std::getenv("CAMSIM_PYTHON");
  const std::string python = env && *env ? env : "/usr/bin/python3";
  if (runProcess({python, "-c", "import matplotlib"}, true) != 0) return std::nullopt;
  return python;
}

void runPythonScript(const std::string& python, std::string_view script,
                     const std::vector<std::string>& args) {
  std::vector<std::string> argv = {python, "-c", std::string(script)};
  argv.insert(argv.end(), args.begin(), args.end());
  const int rc = runProcess(argv, false);
  if (rc != 0)
    throw std::runtime_error("the plot script failed (" + python + " exit status " +
                             std::to_string(rc) + ")");
}

}  // namespace camsim
