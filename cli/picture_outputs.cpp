#include "cli/picture_outputs.h"

#include <cmath>

#include "sensor/io/exr_io.h"
#include "sensor/io/png_io.h"
#include "sensor/isp/color_correction.h"
#include "sensor/spectra/color_space.h"

namespace camsim {

DisplayChoice checkPictureSettings(const PictureSettings& settings) {
  const OcioProcessor ocio(settings.ocioConfig);
  return ocio.resolve(settings.choice);
}

Image xyzToExposedAcescg(const Image& xyz, double& exposure) {
  double sum = 0.0;
  size_t n = 0;
  const int y = xyz.channelIndex("Y");
  for (int j = 0; j < xyz.height; ++j)
    for (int i = 0; i < xyz.width; ++i)
      if (const float v = xyz.at(i, j, y); std::isfinite(v)) sum += static_cast<double>(v), ++n;
  const double mean = n ? sum / static_cast<double>(n) : 0.0;
  exposure = mean > 0.0 ? 0.18 / mean : 1.0;
  return applyColorMatrix(xyz, xyzD65ToWorkingSpace(RgbColorSpace::acesCg()) * exposure,
                          {"R", "G", "B"});
}

JsonObject writePicture(const Image& acescg, const std::string& name,
                        const PictureSettings& settings, bool writeExrFile, const Metadata& meta,
                        OutputSet& outputs) {
  const OcioProcessor ocio(settings.ocioConfig);
  const DisplayChoice choice = ocio.resolve(settings.choice);
  const Image display = ocio.toDisplay(acescg, choice);
  const bool srgb = choice.display == "sRGB";
  writePng8(outputs.add(name + ".png"), display.width, display.height,
            quantizeDisplay8(display.pixels), srgb);
  if (writeExrFile) {
    const RgbColorSpace& ap1 = RgbColorSpace::acesCg();
    Metadata m = meta;
    m.emplace_back("camsim:color_space", "ACEScg (AP1 primaries, ACES white), scene-linear");
    writeExr(outputs.add(name + "_acescg.exr"), acescg, m,
             ExrChromaticities{ap1.red(), ap1.green(), ap1.blue(), ap1.white()});
  }
  JsonObject used;
  used.set("config", ocio.location().path.string())
      .set("config_origin", describeOcioConfigOrigin(ocio.location().origin))
      .set("input_color_space", ocio.inputColorSpace())
      .set("display", choice.display)
      .set("view", choice.view)
      .set("look", choice.looks)
      .set("png", name + ".png");
  return used;
}

}  // namespace camsim
