// The e-SFR of several channels of one image (slanted_edge.h per channel), the entry point
// for `camsim mtf` and for whatever hands over an image in memory (a capture's film or
// developed image, a scene-generated edge behind a lens): read the file, pick the channels,
// measure each, format the CSV and the JSON.
//
//   channel   meaning
//   R, G, B   the image's channels of those names (camsim's NAME.exr: linear Rec.709)
//   Y         relative luminance Y = w_R·R + w_G·G + w_B·B, the weights the row of
//             xyzFromRgb that gives Y for the image's primaries and white (Rec.709:
//             0.2126, 0.7152, 0.0722); a one-channel image's only channel; or a channel
//             named Y
//   all       R, G, B and Y (a one-channel image: its channel, as Y)
//   other     any channel of the image by its exact name (e.g. XYZ.Y)
// A selection is one of these or several separated by commas ("R,G"). Each channel gets
// its own edge fit, so the edge positions differ by the lateral colour (misregistration,
// sfrmat's fourth column, reported against G when there is one).
//
// The image read from a file: an OpenEXR (camsim's NAME.exr: R, G, B linear Rec.709 and
// more layers; any EXR with named channels) or a PNG.
//
//   file   channels kept                 values                     Y weights
//   EXR    every channel, by its name    as stored (linear)         from the file's
//                                                                   chromaticities, else
//                                                                   Rec.709
//   PNG    grey → Y; RGB(A) → R, G, B    sample/(2^bits − 1), then  Rec.709
//          (alpha dropped)               the sRGB decoding unless
//                                        `linear`
// An e-SFR needs linear values (ISO 12233 applies the inverse OECF first). camsim's PNG is
// a display picture through a tone curve (OpenColorIO's view): decoding its sRGB does not
// undo that curve, so measure NAME.exr; a PNG from elsewhere is decoded as sRGB, or taken
// as is with `linear`.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "sensor/base/image.h"
#include "sensor/measure/slanted_edge.h"
#include "sensor/spectra/cie.h"

namespace camsim {

struct MtfImage {
  Image image;
  std::array<double, 3> yWeights{};  // Y = w·(R, G, B)
  std::string format;                // "exr" or "png"
  std::string encoding;              // "linear" or "sRGB decoded"
};

// The file by its first bytes (EXR or PNG); InputError naming the file if it is missing,
// neither, or unreadable.
MtfImage readMtfImage(const std::filesystem::path& path, bool pngIsLinear);

// Y of linear RGB with these primaries and white (each row of xyzFromRgb scaled so that
// RGB = (1,1,1) is the white with Y = 1).
std::array<double, 3> luminanceWeights(Chromaticity red, Chromaticity green, Chromaticity blue,
                                       Chromaticity white);
std::array<double, 3> rec709LuminanceWeights();

// The selected channels of `image`, one per name, in selection order (duplicates dropped).
// InputError (file `source`, key "channel") for a name the image cannot give.
Image selectMtfChannels(const Image& image, const std::string& selection,
                        const std::array<double, 3>& yWeights, const std::string& source);

struct MtfChannel {
  std::string name;
  SfrResult sfr;
};

struct MtfMeasurement {
  std::string source;  // the image (a path, or a name for an image in memory)
  EdgeRoi roi;
  SfrOptions options;
  int imageWidth = 0, imageHeight = 0;  // px, the whole image's
  std::vector<MtfChannel> channels;
  // Where the ROI sits (ISO 12233's relative field height): the distance of its centre
  // from the image centre over the half diagonal, 0 at the centre, 1 in a corner; and that
  // distance in px (× the pixel pitch: on the sensor).
  double relativeFieldHeight() const;
  double fieldHeightPx() const;
  // The channel whose edge angle and orientation the report gives: Y, else G, else the
  // first.
  const MtfChannel& reference() const;
};

// Every channel of `image` measured in `roi` (measureSfr each; InputError naming the
// channel for the first that fails).
MtfMeasurement measureMtf(const Image& image, const EdgeRoi& roi, const SfrOptions& options);

// mtf.csv: frequency_cy_px[, frequency_cy_mm], then mtf_<channel> per channel; one row per
// frequency, 0 … 1 cycle/px.
std::string formatMtfCsv(const MtfMeasurement& m);
// mtf.json: format camsim-mtf/1, the source, ROI, options, units, and per channel MTF50
// (cycles/px and /mm), MTF at Nyquist, edge angle, position and misregistration.
std::string formatMtfJson(const MtfMeasurement& m);
// The printed summary: a line per channel with MTF50 and the MTF at Nyquist.
std::string formatMtfSummary(const MtfMeasurement& m);
// mtf_fields.csv, the report over several ROIs (field heights): region (1, 2, …), ROI,
// relative field height, height in px and (with the pitch) mm, then per channel MTF50
// (cycles/px, /mm) and the MTF at Nyquist; one row per region and channel.
std::string formatMtfFieldsCsv(const std::vector<MtfMeasurement>& regions);

}  // namespace camsim
