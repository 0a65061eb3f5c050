// Everything `camsim render` writes after the render loop, in one OutputSet (all files
// appear at once, or none): NAME.exr (CIE XYZ + linear Rec.709, absolute), with a sensor
// the raw frames (sensor_outputs.h) and the developed NAME_acescg.exr, the display PNG
// through OpenColorIO (picture_outputs.h), and NAME.json listing every setting used.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

#include "cli/picture_outputs.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "sensor/io/output_set.h"

namespace camsim {

struct RenderOutputInputs {
  const SceneDescription& description;
  const Scene& scene;
  const RenderResult& result;  // images[0]: XYZ; images[1]: sensor electrons (with a sensor)
  const Metadata& metadata;
  const PictureSettings& picture;
  std::function<Image(double)> rerender;  // sensor film at the exposure stretched by k
};

void writeRenderOutputs(const RenderOutputInputs& in, OutputSet& outputs, std::ostream& log);

// The scene-linear NAME.exr image: R, G, B (linear Rec.709) and the XYZ layer, absolute.
Image xyzExrImage(const Image& xyz);

}  // namespace camsim
