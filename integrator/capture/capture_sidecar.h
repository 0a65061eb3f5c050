// NAME.json's content (capture_writer.h), but for "color", which the picture writer adds:
// the scene, every render, camera, sensor and ISP setting used, and what was modelled.
#pragma once

#include "integrator/capture/capture.h"
#include "sensor/io/json_writer.h"

namespace camsim {

// reproducible: leave out the render's wall time (render.seconds), the one value that
// differs between two runs of the same scene, seed and build.
JsonObject captureSidecar(const CaptureResult& result, bool reproducible = false);

}  // namespace camsim
