// Rendering one frame of a sequence scene in a test, as captureSequence renders it.
#pragma once

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_description.h"

namespace camsim::test {

// Frame k of d (its own camera and shutter, d.frameCamera(k)) at d's spp, on `threads`
// threads (0: all), with the CIE XYZ film.
inline RenderResult renderSequenceFrame(const SceneDescription& d, int k, int threads = 0) {
  SceneDescription f = d;
  f.camera = d.frameCamera(k);
  RenderOptions o;
  o.spp = d.render.spp;
  o.threads = threads;
  return render(Scene(f), SpectralResponse::cieXyz(), o);
}

}  // namespace camsim::test
