#include "sensor/base/input_error.h"

namespace camsim {
namespace {

// `text` with its control characters as \xNN per byte — C0 but tab and newline, DEL, and C1
// (U+0080–U+009F, two bytes in UTF-8) — which come from the input (a NUL inside a lens-file
// number, a carriage return in a file name): printed raw, a NUL cut the line short and the
// others could move the user's terminal about. Other UTF-8 passes.
constexpr char kHex[] = "0123456789abcdef";

std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  const auto escape = [&out](unsigned char b) {
    out += "\\x";
    out += kHex[b >> 4];
    out += kHex[b & 15];
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto b = static_cast<unsigned char>(text[i]);
    const auto next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0;
    if ((b < 0x20 && b != '\t' && b != '\n') || b == 0x7f) {
      escape(b);
    } else if (b == 0xc2 && next >= 0x80 && next <= 0x9f) {
      escape(b);
      escape(next);
      ++i;
    } else {
      out += text[i];
    }
  }
  return out;
}

}  // namespace

std::string formatInputError(const SourceLocation& where, const std::string& key,
                             const std::string& message) {
  std::string out = where.file.empty() ? std::string("<input>") : printable(where.file);
  if (where.line > 0) {
    out += ":" + std::to_string(where.line);
    if (where.column > 0) out += ":" + std::to_string(where.column);
  }
  out += ": ";
  if (!key.empty()) out += "key '" + printable(key) + "': ";
  out += printable(message);
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
