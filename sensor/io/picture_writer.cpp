#include "sensor/io/picture_writer.h"

#include "sensor/io/exr_io.h"
#include "sensor/io/png_io.h"
#include "sensor/spectra/color_space.h"

namespace camsim {

DisplayChoice checkPictureSettings(const PictureSettings& settings) {
  const OcioProcessor ocio(settings.ocioConfig);
  return ocio.resolve(settings.choice);
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
