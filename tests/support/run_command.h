// Test support: running a program through the shell with its stdout and stderr captured
// into logDir/stdout.txt and logDir/stderr.txt (kept for inspection after a failure).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/text_file.h"

namespace camsim::test {

// A shell word: s in single quotes, embedded quotes escaped.
inline std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct RunResult {
  int exitCode = -1;  // -1: did not exit normally
  std::string out, err;
};

// `commandLine` (shell syntax: environment assignments, quoted words) with its output captured.
inline RunResult runCommand(const std::string& commandLine, const std::filesystem::path& logDir) {
  const std::filesystem::path out = logDir / "stdout.txt", err = logDir / "stderr.txt";
  const std::string command =
      commandLine + " >" + quote(out.string()) + " 2>" + quote(err.string());
  const int status = std::system(command.c_str());
  RunResult r;
  if (status != -1 && WIFEXITED(status)) r.exitCode = WEXITSTATUS(status);
  r.out = readFile(out);
  r.err = readFile(err);
  return r;
}

// The camsim binary under test (CAMSIM_BINARY, defined for every test target) with `args`,
// after the environment assignments `env` ("NAME=value …", may be empty).
inline RunResult runCamsim(const std::string& args, const std::filesystem::path& logDir,
                           const std::string& env = "") {
  return runCommand((env.empty() ? "" : env + " ") + quote(CAMSIM_BINARY) + " " + args, logDir);
}

}  // namespace camsim::test
