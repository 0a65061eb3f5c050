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

InputError::InputError(SourceLocation where, std::string key, std::string message)
    : std::runtime_error(formatInputError(where, key, message)),
      where_(std::move(where)),
      key_(std::move(key)),
      message_(std::move(message)) {}

}  // namespace camsim
