#include "sensor/isp/isp_black_level.h"

#include <string>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

void checkRaw(const RawImage& raw) {
  if (raw.width < 0 || raw.height < 0 ||
      raw.dn.size() != static_cast<size_t>(raw.width) * static_cast<size_t>(raw.height))
    throw InputError({}, "",
                     "raw image holds " + std::to_string(raw.dn.size()) + " values for " +
                         std::to_string(raw.width) + " × " + std::to_string(raw.height) +
                         " photosites");
  if (!(raw.whiteLevelDn > raw.blackLevelDn))
    throw InputError({}, "white_level_dn",
                     "white level " + std::to_string(raw.whiteLevelDn) +
                         " DN is not above the black level " + std::to_string(raw.blackLevelDn));
}

}  // namespace

Image normalizeRaw(const RawImage& raw) {
  checkRaw(raw);
  const bool mosaic = !raw.cfa.isMonochrome() && !raw.cfa.isStacked();
  Image out(raw.width, raw.height, {mosaic ? std::string("CFA") : raw.cfa.channels.front()});
  const double scale = 1.0 / (raw.whiteLevelDn - raw.blackLevelDn);
  for (size_t i = 0; i < raw.dn.size(); ++i)
    out.pixels[i] = static_cast<float>((static_cast<double>(raw.dn[i]) - raw.blackLevelDn) * scale);
  return out;
}

Image normalizeStackedRaw(const std::vector<RawImage>& planes) {
  if (planes.empty()) throw InputError({}, "", "a stacked raw image needs at least one plane");
  const RawImage& first = planes.front();
  std::vector<std::string> names = first.cfa.channels;
  if (names.size() != planes.size())
    throw InputError({}, "cfa",
                     std::to_string(planes.size()) + " planes for " + std::to_string(names.size()) +
                         " channels");
  Image out(first.width, first.height, names);
  const size_t n = planes.size();
  for (size_t c = 0; c < n; ++c) {
    if (planes[c].width != first.width || planes[c].height != first.height)
      throw InputError({}, "", "the planes of a stacked raw image differ in size");
    const Image plane = normalizeRaw(planes[c]);
    for (size_t i = 0; i < plane.pixels.size(); ++i) out.pixels[i * n + c] = plane.pixels[i];
  }
  return out;
}

}  // namespace camsim
