// White balance: per-channel gains that make a neutral surface equal in every channel.
//
//   v′_k(x, y) = g_k · v_k(x, y),   g_k = w_ref / w_k
//
// w is the camera's response to the scene white, estimated in one of three ways:
//   (a) illuminant:  w_k = Σ_λ QE_k(λ) · I(λ) · λ   (1 nm grid; photo-electrons of the
//                    perfect diffuser up to a constant: photons ∝ energy · λ)
//   (b) grey region: w_k = mean of channel k over a region known to be neutral
//   (c) grey world:  w_k = mean of channel k over the whole image (the scene averages grey)
// ref is the reference channel, whose gain is 1: the channel named "G", else "Y", else 0
// (for a Bayer sensor gains = G/c, so G keeps its value and R, B are scaled to match it).
// (b) and (c) work on a demosaicked image (a pixel is skipped when any channel is clipped or
// not finite) or on a mosaic (whole CFA tiles aligned with the tile grid and inside the
// region; a tile is skipped when any photosite is clipped or not finite), so that every
// channel's mean covers the same scene points. "Clipped" means ≥ clipLevel (1 for the
// normalised output of isp_black_level). Gains are applied without clipping: highlight
// handling belongs to a later stage (scene-linear data may exceed 1).
//
// | parameter   | unit                     | default | meaning                                   |
// |-------------|--------------------------|---------|-------------------------------------------|
// | qe          | e⁻/photon                | —       | SensorSpec::qe, one curve per CFA channel |
// | illuminant I| relative spectral power  | —       | scene illuminant (cieIlluminant, …)       |
// | region      | pixels                   | —       | x, y (top-left), width, height            |
// | clipLevel   | normalised signal        | 1.0     | samples ≥ it are excluded from the means  |
// | gains g_k   | —                        | —       | one per camera channel, g_ref = 1         |
//
// A stacked sensor (CfaLayout::isStacked()) has a full image per channel: the mosaic
// overloads treat it as the multi-channel image it is.
#pragma once

#include <string>
#include <vector>

#include "sensor/base/image.h"
#include "sensor/model/cfa.h"
#include "sensor/model/sensor_spec.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

struct PixelRegion {
  int x = 0, y = 0;  // top-left corner, pixels (row 0 = top)
  int width = 0, height = 0;
};

// c_k = Σ_λ QE_k(λ) · R(λ) · I(λ) · λ over the 1 nm grid, one value per QE curve (the
// expected photo-electrons of a surface of reflectance R under I, up to a constant).
std::vector<double> cameraResponse(const std::vector<Spectrum>& qe, const Spectrum& reflectance,
                                   const Spectrum& illuminant);

// Index of "G", else "Y", else 0.
int whiteBalanceReferenceChannel(const std::vector<std::string>& channels);
// g_k = white[ref] / white[k]. Throws InputError if a component is not > 0.
std::vector<double> gainsFromWhite(const std::vector<double>& white, int referenceChannel);

// (a) From the illuminant: the sensor's QE curves (CFA channel order) see the perfect white.
std::vector<double> whiteBalanceFromIlluminant(const SensorSpec& sensor,
                                               const Spectrum& illuminant);
std::vector<double> whiteBalanceFromIlluminant(const std::vector<Spectrum>& qe,
                                               const std::vector<std::string>& channels,
                                               const Spectrum& illuminant);

// (b) From a neutral region of a demosaicked image (gains in the image's channel order) or
// of a one-channel mosaic (gains in cfa.channels order). Throws InputError if the region is
// outside the image or holds no usable pixel/tile.
std::vector<double> whiteBalanceFromRegion(const Image& image, const PixelRegion& region,
                                           double clipLevel = 1.0);
std::vector<double> whiteBalanceFromRegion(const Image& mosaic, const CfaLayout& cfa,
                                           const PixelRegion& region, double clipLevel = 1.0);

// (c) Grey world over the whole image.
std::vector<double> whiteBalanceGreyWorld(const Image& image, double clipLevel = 1.0);
std::vector<double> whiteBalanceGreyWorld(const Image& mosaic, const CfaLayout& cfa,
                                          double clipLevel = 1.0);

// v′ = g_k · v: per channel of an image, or per CFA channel of a one-channel mosaic.
// Throws InputError if the number of gains does not match the channels.
Image applyWhiteBalance(const Image& image, const std::vector<double>& gains);
Image applyWhiteBalance(const Image& mosaic, const CfaLayout& cfa,
                        const std::vector<double>& gains);

}  // namespace camsim
