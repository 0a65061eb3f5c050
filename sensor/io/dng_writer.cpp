#include "sensor/io/dng_writer.h"

#include <tiffio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/matrix.hpp>

#include "sensor/base/check.h"
#include "sensor/base/input_error.h"
#include "sensor/io/tiff_file.h"
#include "sensor/isp/color_correction.h"
#include "sensor/isp/white_balance.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

constexpr std::uint32_t kTagNoiseProfile = 51041;  // DNG 1.3; libtiff 4.5 does not know it

// Tags libtiff does not know, registered on the open file (TIFFCreateDirectory resets the
// field table, so after it): NoiseProfile, DOUBLE, any count (passed as an int).
const TIFFFieldInfo kDngFields[] = {
    {kTagNoiseProfile, TIFF_VARIABLE, TIFF_VARIABLE, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1,
     const_cast<char*>("NoiseProfile")},
};

// A camera RGB scaled so that its largest component is 1 (AsShotNeutral's convention).
glm::dvec3 maxOne(const glm::dvec3& v) {
  return v / std::max({v.x, v.y, v.z});
}

// DNG CFAPlaneColor code of a channel name (R, G, B only), -1 otherwise.
int planeColorCode(const std::string& name) {
  if (name == "R") return 0;
  if (name == "G") return 1;
  if (name == "B") return 2;
  return -1;
}

}  // namespace

namespace {

// The shared chart fit (sensor/isp/color_correction.h), in the XYZ → camera direction, under
// one calibration illuminant.
DngCalibration calibrationUnder(const std::vector<Spectrum>& qe, const std::string& illuminant,
                                int lightSource, const std::filesystem::path& colorCheckerCsv) {
  const ChartSamples chart = colorCheckerSamples(qe, cieIlluminant(illuminant), colorCheckerCsv);
  glm::dmat3 m = fitLinearMap(chart.xyz, chart.camera);
  const glm::dvec3 whiteCamera = m * chart.xyzWhite;
  const double peak = std::max({whiteCamera.x, whiteCamera.y, whiteCamera.z});
  if (!(peak > 0.0))
    throw InputError({}, "qe", "the sensor does not respond to the " + illuminant + " white");
  return {m / peak, lightSource};
}

}  // namespace

int exifLightSource(const std::string& name) {
  static const std::pair<const char*, int> codes[] = {
      {"D50", 23}, {"D55", 20}, {"D65", 21}, {"D75", 22}, {"A", 17},  {"F1", 12},
      {"F5", 12},  {"F7", 12},  {"F8", 13},  {"F10", 13}, {"F2", 14}, {"F6", 14},
      {"F9", 14},  {"F11", 14}, {"F3", 15},  {"F4", 16},  {"F12", 16}};
  for (const auto& [n, code] : codes)
    if (name == n) return code;
  return 0;
}

DngColor dngColorFromQe(const std::vector<Spectrum>& qe, const std::string& illuminant,
                        const std::filesystem::path& colorCheckerCsv) {
  if (qe.size() != 3)
    throw InputError({}, "qe",
                     "DNG colour needs 3 QE curves (R, G, B), got " + std::to_string(qe.size()));
  DngColor color;
  const int code = exifLightSource(illuminant);
  if (illuminant != "D65" && code != 0) {
    color.calibration1 = calibrationUnder(qe, illuminant, code, colorCheckerCsv);
    color.calibration2 = calibrationUnder(qe, "D65", 21, colorCheckerCsv);
  } else {
    color.calibration1 = calibrationUnder(qe, "D65", 21, colorCheckerCsv);
  }
  const std::vector<double> neutral =
      cameraResponse(qe, Spectrum::constant(1.0), cieIlluminant(illuminant));
  if (!(neutral[0] > 0.0 && neutral[1] > 0.0 && neutral[2] > 0.0))
    throw InputError({}, "qe", "a channel of the sensor does not respond to the " + illuminant);
  color.asShotNeutral = maxOne(glm::dvec3(neutral[0], neutral[1], neutral[2]));
  return color;
}

glm::dvec3 dngNeutralFromGains(const std::vector<double>& gains) {
  CAMSIM_CHECK(gains.size() == 3 && gains[0] > 0.0 && gains[1] > 0.0 && gains[2] > 0.0);
  return maxOne(glm::dvec3(1.0 / gains[0], 1.0 / gains[1], 1.0 / gains[2]));
}

std::optional<DngNoiseProfile> dngNoiseProfile(const SensorSpec& spec,
                                               const ExposureSettings& settings, NoiseMode mode) {
  const std::optional<VarianceLine> line = exposedVarianceLine(spec, settings, mode);
  if (!line) return std::nullopt;
  const double range = spec.whiteLevelDn() - spec.blackLevelDn;
  CAMSIM_CHECK(range > 0.0 && line->slopeDn > 0.0);
  return DngNoiseProfile{line->slopeDn / range, line->offsetDn2 / (range * range)};
}

void writeDng(const std::filesystem::path& path, const RawImage& raw, const DngColor& color,
              const Metadata& meta, const DngCapture& capture) {
  CAMSIM_CHECK(raw.width > 0 && raw.height > 0 &&
               raw.dn.size() == static_cast<size_t>(raw.width) * static_cast<size_t>(raw.height));
  const CfaLayout& cfa = raw.cfa;
  const bool mono = cfa.isMonochrome();
  std::vector<std::uint8_t> pattern;
  if (!mono) {
    CAMSIM_CHECK(cfa.width > 0 && cfa.height > 0 &&
                 cfa.tile.size() ==
                     static_cast<size_t>(cfa.width) * static_cast<size_t>(cfa.height));
    for (const int channel : cfa.tile) {
      const int code = planeColorCode(cfa.channels.at(static_cast<size_t>(channel)));
      if (code < 0)
        throw InputError(
            {}, "cfa",
            "DNG output supports R, G, B colour filter arrays only, not '" + cfa.name + "'");
      pattern.push_back(static_cast<std::uint8_t>(code));
    }
  }

  std::string error;
  TiffPtr tif = openTiff(path, "w", error);
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error("cannot write DNG " + path.string() + ": " + what +
                             (error.empty() ? "" : " (" + error + ")"));
  };
  if (!tif) fail("cannot open");
  TIFF* t = tif.get();
  bool ok = true;

  // The EXIF IFD first (TIFFCreateEXIFDirectory returns 0 on success), then IFD0 pointing
  // at it: written in this order, no directory has to be rewritten. Nothing to record: no
  // EXIF IFD (libtiff cannot write an empty directory).
  std::uint64_t exifOffset = 0;
  const bool exif = capture.exposureTimeS > 0.0 || capture.fNumber > 0.0 ||
                    capture.focalLengthMm > 0.0 || capture.iso > 0.0 ||
                    !capture.dateTimeOriginal.empty() || capture.exposureBiasEv.has_value();
  if (exif) {
    if (TIFFCreateEXIFDirectory(t) != 0) fail("cannot create the EXIF directory");
    if (capture.exposureTimeS > 0.0)
      ok = ok && TIFFSetField(t, EXIFTAG_EXPOSURETIME, capture.exposureTimeS) == 1;
    if (capture.fNumber > 0.0) ok = ok && TIFFSetField(t, EXIFTAG_FNUMBER, capture.fNumber) == 1;
    if (capture.focalLengthMm > 0.0)
      ok = ok && TIFFSetField(t, EXIFTAG_FOCALLENGTH, capture.focalLengthMm) == 1;
    if (capture.iso > 0.0) {
      // ISOSpeedRatings is a SHORT: at 65535 and above, Exif 2.3's rule — 65535 there, the
      // value in ISOSpeed (LONG) with SensitivityType 3 (ISO speed). Below, the tag alone (the
      // same bytes as before).
      const auto rounded = static_cast<std::uint32_t>(std::lround(std::min(capture.iso, 4.0e9)));
      const std::uint16_t iso[1] = {static_cast<std::uint16_t>(std::min(rounded, 65535u))};
      ok = ok && TIFFSetField(t, EXIFTAG_ISOSPEEDRATINGS, 1, iso) == 1;
      if (rounded >= 65535u) {
        ok = ok && TIFFSetField(t, EXIFTAG_SENSITIVITYTYPE, 3) == 1;
        ok = ok && TIFFSetField(t, EXIFTAG_ISOSPEED, rounded) == 1;
      }
    }
    if (!capture.dateTimeOriginal.empty())
      ok = ok && TIFFSetField(t, EXIFTAG_DATETIMEORIGINAL, capture.dateTimeOriginal.c_str()) == 1;
    if (capture.exposureBiasEv)  // SRATIONAL, passed as a double
      ok = ok && TIFFSetField(t, EXIFTAG_EXPOSUREBIASVALUE, *capture.exposureBiasEv) == 1;
    if (!ok || TIFFWriteCustomDirectory(t, &exifOffset) != 1)
      fail("cannot write the EXIF directory");
    TIFFFreeDirectory(t);
  }
  if (TIFFCreateDirectory(t) != 0) fail("cannot start IFD0");
  if (TIFFMergeFieldInfo(t, kDngFields, 1) != 0) fail("cannot register the DNG 1.3 tags");
  // Scalars go through varargs: pass them as the promoted type libtiff reads (int/uint32).
  const auto setU32 = [&](uint32_t tag, std::uint32_t v) {
    ok = ok && TIFFSetField(t, tag, v) == 1;
  };
  const auto setU16 = [&](uint32_t tag, int v) { ok = ok && TIFFSetField(t, tag, v) == 1; };
  const auto setText = [&](uint32_t tag, const std::string& s) {
    ok = ok && TIFFSetField(t, tag, s.c_str()) == 1;
  };

  setU32(TIFFTAG_SUBFILETYPE, 0);
  setU32(TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(raw.width));
  setU32(TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(raw.height));
  setU16(TIFFTAG_BITSPERSAMPLE, 16);
  setU16(TIFFTAG_SAMPLESPERPIXEL, 1);
  setU16(TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
  setU16(TIFFTAG_COMPRESSION, COMPRESSION_NONE);
  setU16(TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  setU16(TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT);
  setU16(TIFFTAG_PHOTOMETRIC, mono ? kPhotometricLinearRaw : PHOTOMETRIC_CFA);
  setU32(TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(t, 0));
  if (exif) ok = ok && TIFFSetField(t, TIFFTAG_EXIFIFD, exifOffset) == 1;

  const std::string* sensorName = findMetadata(meta, "camsim:sensor");
  const std::string sensor = sensorName ? *sensorName : std::string();
  const std::string model = sensor.empty() ? "camsim" : "camsim " + sensor;
  setText(TIFFTAG_MAKE, "camsim");
  setText(TIFFTAG_MODEL, model);
  setText(TIFFTAG_UNIQUECAMERAMODEL, model);
  setText(TIFFTAG_SOFTWARE, std::string("camsim ") + CAMSIM_VERSION);
  std::string description;
  for (const auto& [key, value] : meta) description += key + ": " + value + "\n";
  if (!description.empty()) setText(TIFFTAG_IMAGEDESCRIPTION, description);

  const std::uint8_t dngVersion[4] = {1, 4, 0, 0};
  const std::uint8_t dngBackward[4] = {1, 1, 0, 0};
  ok = ok && TIFFSetField(t, TIFFTAG_DNGVERSION, dngVersion) == 1;
  ok = ok && TIFFSetField(t, TIFFTAG_DNGBACKWARDVERSION, dngBackward) == 1;

  const std::uint16_t repeatOne[2] = {1, 1};
  const float black[1] = {static_cast<float>(raw.blackLevelDn)};
  const std::uint32_t white[1] = {static_cast<std::uint32_t>(std::lround(raw.whiteLevelDn))};
  ok = ok && TIFFSetField(t, TIFFTAG_BLACKLEVELREPEATDIM, repeatOne) == 1;
  ok = ok && TIFFSetField(t, TIFFTAG_BLACKLEVEL, 1, black) == 1;
  ok = ok && TIFFSetField(t, TIFFTAG_WHITELEVEL, 1, white) == 1;
  // SRATIONAL, passed as a double (libtiff stores it as a float: EV to ~7 digits).
  ok = ok && TIFFSetField(t, TIFFTAG_BASELINEEXPOSURE, capture.baselineExposureEv) == 1;
  if (capture.noiseProfile) {
    // One (S, O) pair per colour plane (DNG: count 2 or 2·ColorPlanes), the same for each.
    const int planes = mono ? 1 : 3;
    std::vector<double> profile;
    for (int p = 0; p < planes; ++p)
      profile.insert(profile.end(), {capture.noiseProfile->scale, capture.noiseProfile->offset});
    ok = ok &&
         TIFFSetField(t, kTagNoiseProfile, static_cast<int>(profile.size()), profile.data()) == 1;
  }

  if (!mono) {
    const std::uint16_t repeat[2] = {static_cast<std::uint16_t>(cfa.height),
                                     static_cast<std::uint16_t>(cfa.width)};
    const std::uint8_t planeColor[3] = {0, 1, 2};
    ok = ok && TIFFSetField(t, TIFFTAG_CFAREPEATPATTERNDIM, repeat) == 1;
    ok = ok &&
         TIFFSetField(t, TIFFTAG_CFAPATTERN, static_cast<int>(pattern.size()), pattern.data()) == 1;
    ok = ok && TIFFSetField(t, TIFFTAG_CFAPLANECOLOR, 3, planeColor) == 1;
    setU16(TIFFTAG_CFALAYOUT, 1);
    const auto setMatrix = [&](uint32_t matrixTag, uint32_t illuminantTag,
                               const DngCalibration& c) {
      float matrix[9];
      for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
          matrix[row * 3 + col] = static_cast<float>(c.xyzToCamera[col][row]);  // glm: [col][row]
      ok = ok && TIFFSetField(t, matrixTag, 9, matrix) == 1;
      setU16(illuminantTag, c.lightSource);
    };
    setMatrix(TIFFTAG_COLORMATRIX1, TIFFTAG_CALIBRATIONILLUMINANT1, color.calibration1);
    if (color.calibration2)
      setMatrix(TIFFTAG_COLORMATRIX2, TIFFTAG_CALIBRATIONILLUMINANT2, *color.calibration2);
    CAMSIM_CHECK(color.asShotNeutral.x > 0.0 && color.asShotNeutral.y > 0.0 &&
                 color.asShotNeutral.z > 0.0);
    const glm::dvec3 n = maxOne(color.asShotNeutral);
    const float neutral[3] = {static_cast<float>(n.x), static_cast<float>(n.y),
                              static_cast<float>(n.z)};
    ok = ok && TIFFSetField(t, TIFFTAG_ASSHOTNEUTRAL, 3, neutral) == 1;
  }
  if (!ok) fail("cannot set a DNG tag");

  std::vector<std::uint16_t> row(static_cast<size_t>(raw.width));
  for (int y = 0; y < raw.height; ++y) {
    const auto begin = raw.dn.begin() + static_cast<std::ptrdiff_t>(y) * raw.width;
    std::copy(begin, begin + raw.width, row.begin());
    if (TIFFWriteScanline(t, row.data(), static_cast<std::uint32_t>(y), 0) != 1)
      fail("cannot write pixels");
  }
  if (TIFFFlush(t) != 1) fail("cannot flush");
  tif.reset();
  if (!error.empty()) fail("libtiff error");
}

}  // namespace camsim
