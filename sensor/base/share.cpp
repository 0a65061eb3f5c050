#include "sensor/base/share.h"

#include <charconv>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

// A whole decimal integer in [lo, hi]; none when the text is anything else.
bool parseBounded(const char* begin, const char* end, std::int64_t lo, std::int64_t hi,
                  std::int64_t& value) {
  if (begin == end || *begin == '-' || *begin == '+') return false;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end && value >= lo && value <= hi;
}

}  // namespace

Share parseShare(const std::string& text, const std::string& key) {
  const std::size_t slash = text.find('/');
  std::int64_t k = 0, m = 0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (slash == std::string::npos || !parseBounded(begin + slash + 1, end, 1, kMaxShareCount, m) ||
      !parseBounded(begin, begin + slash, 0, m - 1, k))
    throw InputError({}, key,
                     "expects k/M (share k of M, 0 <= k < M, 1 <= M <= " +
                         std::to_string(kMaxShareCount) + "), got '" + text + "'");
  return Share{static_cast<int>(k), static_cast<int>(m)};
}

}  // namespace camsim
