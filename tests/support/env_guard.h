// Test support: saves an environment variable, unsets it, and restores it when the guard
// goes out of scope, on every path (a failed ASSERT, an exception) — so a test that sets
// the variable leaves the process as it found it.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

namespace camsim::test {

class EnvGuard {
 public:
  explicit EnvGuard(const char* name) : name_(name) {
    if (const char* v = std::getenv(name)) old_ = v;
    ::unsetenv(name);
  }
  ~EnvGuard() {
    if (old_)
      ::setenv(name_, old_->c_str(), 1);
    else
      ::unsetenv(name_);
  }
  EnvGuard(const EnvGuard&) = delete;
  EnvGuard& operator=(const EnvGuard&) = delete;

  void set(const std::string& value) const { ::setenv(name_, value.c_str(), 1); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace camsim::test
