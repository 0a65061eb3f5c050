// InputError: the one exception type for bad user input (scene files, spectral tables,
// mesh files, command-line values). Library code throws it; only main() turns it into
// exit code 2. Internal invariants use CAMSIM_CHECK instead (see check.h).
#pragma once

#include <stdexcept>
#include <string>

namespace camsim {

// Where in an input file something is. line/column are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

class InputError : public std::runtime_error {
 public:
  // key: the scene key (dotted path such as "shapes[2].radius") or "" when none applies.
  InputError(SourceLocation where, std::string key, std::string message);

  const SourceLocation& where() const { return where_; }
  const std::string& key() const { return key_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string key_;
  std::string message_;
};

// "file:line:col: key 'k': message" with the parts that are known.
std::string formatInputError(const SourceLocation& where, const std::string& key,
                             const std::string& message);

// `inner`, an error inside a file another one named (a sensor description, a table), with
// where it was named: "… (in the file named by FILE:LINE:COL, key 'KEY')".
InputError namedBy(const InputError& inner, const SourceLocation& by, const std::string& key);

// `e` when it knows its file; else the same error in `file` (a stage that found it without
// one: the camera's lens, built from a scene).
InputError inFile(const InputError& e, const std::string& file);

}  // namespace camsim
