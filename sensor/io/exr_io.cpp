#include "sensor/io/exr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfChromaticities.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <charconv>
#include <cmath>

#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {

void writeExr(const std::filesystem::path& path, const Image& image, const Metadata& metadata,
              const std::optional<ExrChromaticities>& chromaticities) {
  CAMSIM_CHECK(image.width > 0 && image.height > 0 && image.channelCount() > 0);
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const auto& [key, value] : metadata) header.insert(key, Imf::StringAttribute(value));
  if (chromaticities) {
    const auto& c = *chromaticities;
    Imf::addChromaticities(header,
                           Imf::Chromaticities(Imath::V2f(float(c.red.x), float(c.red.y)),
                                               Imath::V2f(float(c.green.x), float(c.green.y)),
                                               Imath::V2f(float(c.blue.x), float(c.blue.y)),
                                               Imath::V2f(float(c.white.x), float(c.white.y))));
  }
  Imf::FrameBuffer frame;
  const size_t pixelStride = sizeof(float) * image.channels.size();
  const size_t rowStride = pixelStride * static_cast<size_t>(image.width);
  for (int c = 0; c < image.channelCount(); ++c) {
    header.channels().insert(image.channels[c], Imf::Channel(Imf::FLOAT));
    // OpenEXR wants a non-const base pointer even for writing; it only reads through it.
    char* base = reinterpret_cast<char*>(const_cast<float*>(image.pixels.data() + c));
    frame.insert(image.channels[c], Imf::Slice(Imf::FLOAT, base, pixelStride, rowStride));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(frame);
  file.writePixels(image.height);
}

namespace {

// Chromaticities a colour conversion can use: finite, each y ≠ 0 (xyY → XYZ divides by it;
// ACES AP0's blue primary has y = −0.077), the white's y > 0, and primaries that span a
// plane of chromaticity (found by probing: all six at 0.3 gave NaN luminance weights, and
// camsim mtf blamed a "not finite" pixel of the ROI).
void checkChromaticities(const ExrChromaticities& c, const std::filesystem::path& path) {
  bool usable = c.white.y > 0.0;
  for (const Chromaticity& p : {c.red, c.green, c.blue, c.white})
    usable = usable && std::isfinite(p.x) && std::isfinite(p.y) && std::abs(p.y) > 1e-9;
  const double area =
      (c.green.x - c.red.x) * (c.blue.y - c.red.y) - (c.blue.x - c.red.x) * (c.green.y - c.red.y);
  if (!usable || !(std::abs(area) > 1e-6))
    throw InputError(
        {path.string(), 0, 0}, "chromaticities",
        "the header's chromaticities are not a colour space (red " + formatNumber(c.red.x, 6) +
            ", " + formatNumber(c.red.y, 6) + "; green " + formatNumber(c.green.x, 6) + ", " +
            formatNumber(c.green.y, 6) + "; blue " + formatNumber(c.blue.x, 6) + ", " +
            formatNumber(c.blue.y, 6) + "; white " + formatNumber(c.white.x, 6) + ", " +
            formatNumber(c.white.y, 6) +
            "): each y must be non-zero (the white's positive) and the primaries must not lie on a "
            "line");
}

}  // namespace

ExrFile readExr(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow();
    ExrFile out;
    std::vector<std::string> names;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
      names.emplace_back(it.name());
    out.image = Image(dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, names);
    Imf::FrameBuffer frame;
    const size_t pixelStride = sizeof(float) * names.size();
    const size_t rowStride = pixelStride * static_cast<size_t>(out.image.width);
    for (size_t c = 0; c < names.size(); ++c) {
      char* base = reinterpret_cast<char*>(out.image.pixels.data() + c) -
                   static_cast<ptrdiff_t>(dw.min.x) * static_cast<ptrdiff_t>(pixelStride) -
                   static_cast<ptrdiff_t>(dw.min.y) * static_cast<ptrdiff_t>(rowStride);
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, pixelStride, rowStride));
    }
    file.setFrameBuffer(frame);
    file.readPixels(dw.min.y, dw.max.y);
    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        out.metadata.emplace_back(it.name(), s->value());
    if (Imf::hasChromaticities(header)) {
      const Imf::Chromaticities& c = Imf::chromaticities(header);
      out.chromaticities = ExrChromaticities{{double(c.red.x), double(c.red.y)},
                                             {double(c.green.x), double(c.green.y)},
                                             {double(c.blue.x), double(c.blue.y)},
                                             {double(c.white.x), double(c.white.y)}};
      checkChromaticities(*out.chromaticities, path);
    }
    return out;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError({path.string(), 0, 0}, "", std::string("cannot read EXR: ") + e.what());
  }
}

namespace {}  // namespace

void writeRawExr(const std::filesystem::path& path, const RawImage& raw,
                 const Image& expectedElectrons, const Metadata& meta) {
  CAMSIM_CHECK(raw.width > 0 && raw.height > 0 &&
               raw.dn.size() == static_cast<size_t>(raw.width) * static_cast<size_t>(raw.height));
  CAMSIM_CHECK(expectedElectrons.width == raw.width && expectedElectrons.height == raw.height);
  std::vector<std::string> names = {"raw.DN"};
  for (const auto& c : expectedElectrons.channels) names.push_back("electrons." + c);
  Image image(raw.width, raw.height, names);
  const int electronChannels = expectedElectrons.channelCount();
  for (int y = 0; y < raw.height; ++y)
    for (int x = 0; x < raw.width; ++x) {
      image.at(x, y, 0) = static_cast<float>(raw.at(x, y));
      for (int c = 0; c < electronChannels; ++c)
        image.at(x, y, c + 1) = expectedElectrons.at(x, y, c);
    }
  const Metadata levels = {{"camsim:cfa", raw.cfa.name},
                           {"camsim:black_level_dn", formatShortest(raw.blackLevelDn)},
                           {"camsim:white_level_dn", formatShortest(raw.whiteLevelDn)}};
  Metadata all;
  for (const auto& entry : meta) {
    bool replaced = false;
    for (const auto& level : levels) replaced = replaced || level.first == entry.first;
    if (!replaced) all.push_back(entry);
  }
  all.insert(all.end(), levels.begin(), levels.end());
  writeExr(path, image, all, std::nullopt);
}

}  // namespace camsim
