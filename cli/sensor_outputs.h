// The sensor stage of `camsim render`: from the noise-free expected electrons of a render
// to raw frames on disk — auto-exposure (metering on the noise-free signal), exposure
// brackets, noise and ADC (sensor::expose), raw DNG and raw EXR.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "integrator/scene/scene_description.h"
#include "sensor/base/image.h"
#include "sensor/io/dng_writer.h"
#include "sensor/io/output_set.h"
#include "sensor/isp/isp_pipeline.h"
#include "sensor/model/raw_image.h"

namespace camsim {

struct SensorFrameReport {
  double exposureTimeS = 0.0;  // effective, after auto-exposure and bracketing
  double ev = 0.0;
  double clippedFraction = 0.0;  // photosites at the white level
  std::string dngFile, rawExrFile;
};

struct SensorOutputs {
  std::vector<SensorFrameReport> frames;
  std::vector<RawImage> referenceRaws;  // the 0 EV frame (or the first bracket): one per plane
  double exposureScale = 1.0;           // auto-exposure factor applied to every frame
};

// electrons: the render's sensor film (expected e⁻ at the scene's exposure, T_eff).
// rerender(k): renders again with the shutter stretched by k and returns the new
// electrons — used only when the scene moves (motion blur depends on the exposure);
// static scenes scale linearly. Writes NAME[_evX].dng and NAME[_evX]_raw.exr (a stacked
// sensor: NAME[_evX]_raw_<channel>.exr per plane, no DNG). Each DNG carries the white
// balance `isp` develops that frame with and capture's EXIF fields, with the frame's own
// exposure time and ISO.
SensorOutputs writeSensorFrames(const SensorSettings& sensor, const IspSettings& isp,
                                const DngCapture& capture, const std::string& name,
                                double exposureTimeS, bool sceneMoves, const Image& electrons,
                                const std::function<Image(double)>& rerender, const Metadata& meta,
                                OutputSet& outputs, std::ostream& log);

}  // namespace camsim
