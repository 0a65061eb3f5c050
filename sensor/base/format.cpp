#include "sensor/base/format.h"

#include <charconv>
#include <cstdio>

namespace camsim {

std::string formatNumber(double v, int precision) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  return buf;
}

std::string formatRange(double lo, double hi, bool loOpen) {
  return (loOpen ? "(" : "[") + formatNumber(lo, 10) + ", " + formatNumber(hi, 10) + "]";
}

std::string formatShortest(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

std::string formatFixed(double v, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string formatRate(double perSecond) {
  if (perSecond >= 1e6) return formatFixed(perSecond * 1e-6, 2) + " M";
  if (perSecond >= 1e3) return formatFixed(perSecond * 1e-3, 2) + " k";
  return formatFixed(perSecond, 2) + " ";
}

std::string formatSize(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

std::string formatSixDigits(long long v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%06lld", v);
  return buf;
}

}  // namespace camsim
