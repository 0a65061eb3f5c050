#include "sensor/base/input_error.h"

namespace camsim {

std::string formatInputError(const SourceLocation& where, const std::string& key,
                             const std::string& message) {
  std::string out = where.file.empty() ? std::string("<input>") : where.file;
  if (where.line > 0) {
    out += ":" + std::to_string(where.line);
    if (where.column > 0) out += ":" + std::to_string(where.column);
  }
  out += ": ";
  if (!key.empty()) out += "key '" + key + "': ";
  out += message;
  return out;
}

InputError namedBy(const InputError& inner, const SourceLocation& by, const std::string& key) {
  std::string named = by.file;
  if (by.line > 0) named += ":" + std::to_string(by.line) + ":" + std::to_string(by.column);
  return InputError(inner.where(), inner.key(),
                    inner.message() + " (in the file named by " + named + ", key '" + key + "')");
}

InputError inFile(const InputError& e, const std::string& file) {
  if (!e.where().file.empty()) return e;
  return InputError({file, 0, 0}, e.key(), e.message());
}

InputError::InputError(SourceLocation where, std::string key, std::string message)
    : std::runtime_error(formatInputError(where, key, message)),
      where_(std::move(where)),
      key_(std::move(key)),
      message_(std::move(message)) {}

}  // namespace camsim
