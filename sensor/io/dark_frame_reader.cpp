#include "sensor/io/dark_frame_reader.h"

#include <tiffio.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/tiff_file.h"

namespace camsim {
namespace fs = std::filesystem;
namespace {

constexpr std::uint32_t kMaxSide = 1u << 16;

RawImage readRawExrFrame(const fs::path& path) {
  const ExrFile exr = readExr(path);
  const Image& image = exr.image;
  const int channel = image.channelIndex("raw.DN");
  if (channel < 0)
    throw InputError({path.string(), 0, 0}, "dark_frames",
                     "no 'raw.DN' channel: not a camsim raw EXR (" + path.string() + ")");
  RawImage raw;
  raw.width = image.width;
  raw.height = image.height;
  raw.dn.resize(static_cast<size_t>(raw.width) * static_cast<size_t>(raw.height));
  for (int y = 0; y < raw.height; ++y)
    for (int x = 0; x < raw.width; ++x) {
      const float v = image.at(x, y, channel);
      if (!(v >= 0.0f && v <= 65535.0f) || v != std::floor(v))
        throw InputError({path.string(), 0, 0}, "dark_frames",
                         "raw.DN holds a value that is not a 16-bit integer at (" +
                             std::to_string(x) + ", " + std::to_string(y) + ")");
      raw.dn[static_cast<size_t>(y) * static_cast<size_t>(raw.width) + static_cast<size_t>(x)] =
          static_cast<std::uint16_t>(v);
    }
  raw.blackLevelDn = 0.0;
  if (const std::string* black = findMetadata(exr.metadata, "camsim:black_level_dn")) {
    try {
      raw.blackLevelDn = std::stod(*black);
    } catch (const std::exception&) {
      throw InputError({path.string(), 0, 0}, "dark_frames",
                       "camsim:black_level_dn '" + *black + "' is not a number");
    }
  }
  return raw;
}

}  // namespace

RawImage readRawDng(const fs::path& path) {
  std::string error;
  const TiffPtr tif = openTiff(path, "r", error);
  const auto fail = [&](const std::string& what) {
    throw InputError({path.string(), 0, 0}, "dark_frames",
                     "cannot read the DNG " + path.string() + ": " + what +
                         (error.empty() ? "" : " (" + error + ")"));
  };
  if (!tif) fail("not a TIFF/DNG file");
  TIFF* t = tif.get();
  std::uint32_t width = 0, height = 0;
  std::uint16_t bits = 0, samples = 1, compression = 1, photometric = 0;
  if (TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &width) != 1 ||
      TIFFGetField(t, TIFFTAG_IMAGELENGTH, &height) != 1)
    fail("no image size");
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &samples);
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
  TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photometric);
  if (width == 0 || height == 0 || width > kMaxSide || height > kMaxSide)
    fail("image size " + std::to_string(width) + "×" + std::to_string(height) +
         " outside 1 … 65536");
  if (photometric != PHOTOMETRIC_CFA && photometric != kPhotometricLinearRaw)
    fail("IFD0 is not a raw image (PhotometricInterpretation " + std::to_string(photometric) +
         ", expected CFA or LinearRaw)");
  if (bits != 16 || samples != 1 || compression != COMPRESSION_NONE || TIFFIsTiled(t))
    fail("only uncompressed, untiled 16-bit one-sample raw data is read (this file: " +
         std::to_string(bits) + " bit, " + std::to_string(samples) + " samples, compression " +
         std::to_string(compression) + (TIFFIsTiled(t) ? ", tiled" : "") + ")");
  if (TIFFScanlineSize64(t) != static_cast<std::uint64_t>(width) * 2u) fail("unexpected row size");
  // Uncompressed 16-bit data must be in the file: a header that claims more is refused
  // before anything is allocated (a 600-byte file claimed 65536 × 31000 pixels: 4 GB).
  std::error_code sizeError;
  const std::uintmax_t fileBytes = fs::file_size(path, sizeError);
  const std::uint64_t dataBytes = static_cast<std::uint64_t>(width) * height * 2u;
  if (sizeError || dataBytes > fileBytes)
    fail("its " + std::to_string(width) + "×" + std::to_string(height) + " 16-bit raw data needs " +
         std::to_string(dataBytes) + " bytes, the file has " +
         std::to_string(sizeError ? 0 : fileBytes));

  RawImage raw;
  raw.width = static_cast<int>(width);
  raw.height = static_cast<int>(height);
  raw.dn.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
  for (std::uint32_t y = 0; y < height; ++y)
    if (TIFFReadScanline(t, raw.dn.data() + static_cast<size_t>(y) * width, y, 0) != 1)
      fail("cannot read row " + std::to_string(y));

  std::uint16_t count = 0;
  float* black = nullptr;
  if (TIFFGetField(t, TIFFTAG_BLACKLEVEL, &count, &black) == 1 && count > 0 && black) {
    for (std::uint16_t i = 1; i < count; ++i)
      if (black[i] != black[0]) fail("per-position black levels are not supported");
    if (!std::isfinite(black[0]) || black[0] < 0.0f || black[0] > 65535.0f)
      fail("BlackLevel outside [0, 65535]");
    raw.blackLevelDn = static_cast<double>(black[0]);
  }
  std::uint16_t whiteCount = 0;
  std::uint32_t* white = nullptr;
  if (TIFFGetField(t, TIFFTAG_WHITELEVEL, &whiteCount, &white) == 1 && whiteCount > 0 && white)
    raw.whiteLevelDn = static_cast<double>(std::min<std::uint32_t>(white[0], 65535u));
  return raw;
}

DarkFrameSet loadDarkFrames(const fs::path& dir, const SensorSpec& sensor) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if ((ext == ".dng" || ext == ".exr") && entry.is_regular_file(ec))
      files.push_back(entry.path());
  }
  if (ec)
    throw InputError({dir.string(), 0, 0}, "dark_frames",
                     "cannot list the dark-frame directory: " + ec.message());
  if (files.empty())
    throw InputError({dir.string(), 0, 0}, "dark_frames",
                     "no dark frames (*.dng, *.exr) in " + dir.string());
  std::sort(files.begin(), files.end());
  DarkFrameSet set;
  for (const fs::path& f : files) {
    std::string ext = f.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    RawImage raw = ext == ".dng" ? readRawDng(f) : readRawExrFrame(f);
    const auto mismatch = [&f](const std::string& what) {
      throw InputError({f.string(), 0, 0}, "dark_frames", what);
    };
    if (set.frames.empty()) {
      set.width = raw.width;
      set.height = raw.height;
      set.blackLevelDn = raw.blackLevelDn;
    } else if (raw.width != set.width || raw.height != set.height) {
      mismatch("size " + std::to_string(raw.width) + "×" + std::to_string(raw.height) +
               " differs from the first frame's " + std::to_string(set.width) + "×" +
               std::to_string(set.height));
    } else if (raw.blackLevelDn != set.blackLevelDn) {
      mismatch("black level differs from the first frame's");
    }
    if (raw.blackLevelDn != sensor.blackLevelDn)
      mismatch("black level " + formatShortest(raw.blackLevelDn) + " DN differs from the sensor '" +
               sensor.name + "''s " + formatShortest(sensor.blackLevelDn) + " DN");
    const auto top = *std::max_element(raw.dn.begin(), raw.dn.end());
    if (top > sensor.whiteLevelDn())
      mismatch("holds " + std::to_string(top) + " DN, above the sensor's white level " +
               formatShortest(sensor.whiteLevelDn()));
    set.frames.push_back(std::move(raw.dn));
    set.names.push_back(f.filename().string());
  }
  return set;
}

std::optional<DarkFrameSet> darkFramesFor(const SensorSpec& sensor, NoiseMode mode) {
  if (sensor.darkFramesDir.empty() || mode != NoiseMode::kFull || sensor.noiseless)
    return std::nullopt;
  return loadDarkFrames(sensor.darkFramesDir, sensor);
}

}  // namespace camsim
