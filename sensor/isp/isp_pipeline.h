// The image pipeline: raw DN → scene-linear working-space RGB (ACEScg by default), each
// stage a function on plain images (sensor/isp/isp_black_level.h, white_balance.h,
// demosaic.h, color_correction.h). developRaw() runs them in order:
//
//   1. normalise:     n = (DN − black) / (white − black)
//   2. white balance: per CFA channel, n_k · g_k with g from the scene illuminant (camera
//                     response Σ QE_k·I·λ), a grey region, or grey-world; then clipped
//                     at min_k g_k so saturated highlights stay neutral
//   3. demosaic:      Malvar–He–Cutler (default) or bilinear; stacked sensors skip it
//   4. colour:        working RGB = W · M · balanced camera RGB, M the CCM fitted on the 24
//                     ColorChecker reflectances under `ccmIlluminant` from the sensor's own
//                     QE curves (never hard-coded), W = XYZ(D65) → working space
//   5. exposure:      × 1 (values are fractions of the sensor's saturation; 0.18 ≈ the
//                     auto-exposure target)
// An ideal XYZ (stacked) sensor skips demosaic and the CCM: its channels are XYZ. Its white
// balance is a chromatic adaptation: the gains (from the illuminant, a region or grey world,
// as for a mosaic) give the XYZ of the scene white, w = (1/g_X, 1, 1/g_Z), and the planes
// go through Bradford B(w → D65 white) — the adaptation the Bayer path's CCM builds in —
// so its greys come out neutral under any illuminant.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sensor/base/image.h"
#include "sensor/isp/color_correction.h"
#include "sensor/isp/demosaic.h"
#include "sensor/isp/white_balance.h"
#include "sensor/model/raw_image.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {

struct IspSettings {
  enum class WhiteBalance { kIlluminant, kRegion, kGreyWorld };
  WhiteBalance whiteBalance = WhiteBalance::kIlluminant;
  std::string illuminant = "D65";  // CIE illuminant name for kIlluminant and the CCM fit
  PixelRegion region;              // for kRegion
  DemosaicMethod demosaic = DemosaicMethod::kMalvarHeCutler;
};
// The scene's `isp.white_balance` names, also Python's and the sidecar's
// (sensor/base/enum_names.h).
template <>
struct EnumNames<IspSettings::WhiteBalance> {
  using W = IspSettings::WhiteBalance;
  static constexpr EnumName<W> kTable[] = {
      {W::kIlluminant, "illuminant"}, {W::kRegion, "region"}, {W::kGreyWorld, "grey_world"}};
};

struct DevelopedImage {
  Image working;                     // R, G, B in the working space (ACEScg)
  std::vector<double> whiteBalance;  // gains per camera channel (reference channel = 1)
  ColorCorrection colorCorrection;   // the fitted CCM (stacked: the adaptation) and matrices
};

// The white-balance gains developRaw applies, per camera channel (G, else Y, = 1), from the
// same raws: a raw converter's AsShotNeutral is 1/g (sensor/io/dng_writer.h).
std::vector<double> whiteBalanceGains(const std::vector<RawImage>& raws, const SensorSpec& sensor,
                                      const IspSettings& settings);

// raws: one RawImage for a mosaic sensor, one per channel for a stacked sensor. gains:
// whiteBalanceGains() of the same raws and settings when the caller has them already.
DevelopedImage developRaw(const std::vector<RawImage>& raws, const SensorSpec& sensor,
                          const IspSettings& settings, const std::filesystem::path& colorCheckerCsv,
                          const std::vector<double>* gains = nullptr);

// The developed image as R, G, B: the working image itself, or a monochrome sensor's one
// plane as grey RGB (a capture's picture, camsim.develop()).
Image workingRgb(const DevelopedImage& developed);

}  // namespace camsim
