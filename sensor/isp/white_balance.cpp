#include "sensor/isp/white_balance.h"

#include <cmath>
#include <cstdint>
#include <string>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

void checkRegion(const Image& image, const PixelRegion& r) {
  // In 64 bits: x + width past INT_MAX wrapped negative and passed (found by probing Python's
  // develop(): a segfault reading outside the image).
  if (r.width <= 0 || r.height <= 0 || r.x < 0 || r.y < 0 ||
      std::int64_t{r.x} + r.width > image.width || std::int64_t{r.y} + r.height > image.height)
    throw InputError({}, "region",
                     "white-balance region (" + std::to_string(r.x) + ", " + std::to_string(r.y) +
                         ", " + std::to_string(r.width) + " × " + std::to_string(r.height) +
                         ") is empty or outside the " + std::to_string(image.width) + " × " +
                         std::to_string(image.height) + " image");
}

bool usable(float v, double clipLevel) {
  return std::isfinite(v) && static_cast<double>(v) < clipLevel;
}

// Per-channel means over the pixels of a region with no clipped channel.
std::vector<double> regionMeans(const Image& image, const PixelRegion& r, double clipLevel) {
  checkRegion(image, r);
  const int n = image.channelCount();
  std::vector<double> sum(static_cast<size_t>(n), 0.0);
  long count = 0;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) {
      bool ok = true;
      for (int c = 0; c < n && ok; ++c) ok = usable(image.at(x, y, c), clipLevel);
      if (!ok) continue;
      for (int c = 0; c < n; ++c)
        sum[static_cast<size_t>(c)] += static_cast<double>(image.at(x, y, c));
      ++count;
    }
  if (count == 0) throw InputError({}, "region", "no unclipped pixel in the white-balance region");
  for (double& s : sum) s /= static_cast<double>(count);
  return sum;
}

// Per-CFA-channel means over the whole tiles (aligned with the tile grid) inside a region.
std::vector<double> mosaicRegionMeans(const Image& mosaic, const CfaLayout& cfa,
                                      const PixelRegion& r, double clipLevel) {
  if (mosaic.channelCount() != 1)
    throw InputError({}, "",
                     "a mosaic has one channel, got " + std::to_string(mosaic.channelCount()));
  checkRegion(mosaic, r);
  const size_t n = cfa.channels.size();
  std::vector<double> sum(n, 0.0);
  std::vector<long> count(n, 0);
  const int x0 = (r.x + cfa.width - 1) / cfa.width * cfa.width;
  const int y0 = (r.y + cfa.height - 1) / cfa.height * cfa.height;
  for (int ty = y0; ty + cfa.height <= r.y + r.height; ty += cfa.height)
    for (int tx = x0; tx + cfa.width <= r.x + r.width; tx += cfa.width) {
      bool ok = true;
      for (int y = ty; y < ty + cfa.height && ok; ++y)
        for (int x = tx; x < tx + cfa.width && ok; ++x) ok = usable(mosaic.at(x, y, 0), clipLevel);
      if (!ok) continue;
      for (int y = ty; y < ty + cfa.height; ++y)
        for (int x = tx; x < tx + cfa.width; ++x) {
          const auto c = static_cast<size_t>(cfa.channelAt(x, y));
          sum[c] += static_cast<double>(mosaic.at(x, y, 0));
          ++count[c];
        }
    }
  for (size_t c = 0; c < n; ++c) {
    if (count[c] == 0)
      throw InputError({}, "region", "no unclipped CFA tile in the white-balance region");
    sum[c] /= static_cast<double>(count[c]);
  }
  return sum;
}

}  // namespace

std::vector<double> cameraResponse(const std::vector<Spectrum>& qe, const Spectrum& reflectance,
                                   const Spectrum& illuminant) {
  std::vector<double> response;
  response.reserve(qe.size());
  for (const Spectrum& curve : qe) {
    double sum = 0.0;
    for (int i = 0; i < kSpectrumSamples; ++i)
      sum += static_cast<double>(curve.sample(i)) * static_cast<double>(reflectance.sample(i)) *
             static_cast<double>(illuminant.sample(i)) * static_cast<double>(kLambdaMinNm + i);
    response.push_back(sum);
  }
  return response;
}

int whiteBalanceReferenceChannel(const std::vector<std::string>& channels) {
  for (const char* name : {"G", "Y"})
    for (size_t i = 0; i < channels.size(); ++i)
      if (channels[i] == name) return static_cast<int>(i);
  return 0;
}

std::vector<double> gainsFromWhite(const std::vector<double>& white, int referenceChannel) {
  CAMSIM_CHECK(referenceChannel >= 0 && static_cast<size_t>(referenceChannel) < white.size());
  std::vector<double> gains;
  for (size_t k = 0; k < white.size(); ++k) {
    if (!(white[k] > 0.0) || !std::isfinite(white[k]))
      throw InputError({}, "white_balance",
                       "channel " + std::to_string(k) + " has no positive response to the white (" +
                           std::to_string(white[k]) + "): cannot white-balance");
    gains.push_back(white[static_cast<size_t>(referenceChannel)] / white[k]);
  }
  return gains;
}

std::vector<double> whiteBalanceFromIlluminant(const std::vector<Spectrum>& qe,
                                               const std::vector<std::string>& channels,
                                               const Spectrum& illuminant) {
  if (qe.size() != channels.size() || qe.empty())
    throw InputError({}, "qe",
                     "white balance needs one QE curve per channel (" + std::to_string(qe.size()) +
                         " curves, " + std::to_string(channels.size()) + " channels)");
  return gainsFromWhite(cameraResponse(qe, Spectrum::constant(1.0), illuminant),
                        whiteBalanceReferenceChannel(channels));
}

std::vector<double> whiteBalanceFromIlluminant(const SensorSpec& sensor,
                                               const Spectrum& illuminant) {
  return whiteBalanceFromIlluminant(sensor.qe, sensor.cfa.channels, illuminant);
}

std::vector<double> whiteBalanceFromRegion(const Image& image, const PixelRegion& region,
                                           double clipLevel) {
  return gainsFromWhite(regionMeans(image, region, clipLevel),
                        whiteBalanceReferenceChannel(image.channels));
}

std::vector<double> whiteBalanceFromRegion(const Image& mosaic, const CfaLayout& cfa,
                                           const PixelRegion& region, double clipLevel) {
  if (cfa.isStacked()) return whiteBalanceFromRegion(mosaic, region, clipLevel);
  return gainsFromWhite(mosaicRegionMeans(mosaic, cfa, region, clipLevel),
                        whiteBalanceReferenceChannel(cfa.channels));
}

std::vector<double> whiteBalanceGreyWorld(const Image& image, double clipLevel) {
  return whiteBalanceFromRegion(image, {0, 0, image.width, image.height}, clipLevel);
}

std::vector<double> whiteBalanceGreyWorld(const Image& mosaic, const CfaLayout& cfa,
                                          double clipLevel) {
  return whiteBalanceFromRegion(mosaic, cfa, {0, 0, mosaic.width, mosaic.height}, clipLevel);
}

Image applyWhiteBalance(const Image& image, const std::vector<double>& gains) {
  const size_t n = image.channels.size();
  if (gains.size() != n)
    throw InputError(
        {}, "white_balance",
        std::to_string(gains.size()) + " gains for " + std::to_string(n) + " image channels");
  Image out = image;
  for (size_t i = 0; i < out.pixels.size(); ++i)
    out.pixels[i] = static_cast<float>(static_cast<double>(out.pixels[i]) * gains[i % n]);
  return out;
}

Image applyWhiteBalance(const Image& mosaic, const CfaLayout& cfa,
                        const std::vector<double>& gains) {
  if (cfa.isStacked()) return applyWhiteBalance(mosaic, gains);
  if (mosaic.channelCount() != 1 || gains.size() != cfa.channels.size())
    throw InputError(
        {}, "white_balance",
        "a mosaic white balance needs a one-channel image and one gain per CFA channel (" +
            std::to_string(gains.size()) + " gains, " + std::to_string(cfa.channels.size()) +
            " channels)");
  Image out = mosaic;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      float& v = out.at(x, y, 0);
      v = static_cast<float>(static_cast<double>(v) *
                             gains[static_cast<size_t>(cfa.channelAt(x, y))]);
    }
  return out;
}

}  // namespace camsim
