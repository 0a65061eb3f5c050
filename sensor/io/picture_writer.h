// The picture a person looks at: scene-linear ACEScg → OpenColorIO display/view/look →
// 8-bit PNG, and the scene-linear ACEScg EXR it came from.
#pragma once

#include <filesystem>
#include <string>

#include "sensor/base/image.h"
#include "sensor/io/json_writer.h"
#include "sensor/io/output_set.h"
#include "sensor/isp/color_management.h"

namespace camsim {

struct PictureSettings {
  std::filesystem::path ocioConfig;  // empty: $OCIO, then camsim's luts/config.ocio
  DisplayChoice choice;              // empty fields: the config's defaults
};

// Validates the OCIO config and choice before any rendering (InputError on a bad name).
DisplayChoice checkPictureSettings(const PictureSettings& settings);

// acescg: R, G, B scene-linear ACEScg (already exposed: 0.18 = mid-grey). Writes
// NAME.png through OCIO, and NAME_acescg.exr if writeExr. Returns what was used (JSON).
JsonObject writePicture(const Image& acescg, const std::string& name,
                        const PictureSettings& settings, bool writeExr, const Metadata& meta,
                        OutputSet& outputs);

}  // namespace camsim
