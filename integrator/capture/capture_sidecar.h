// NAME.json's content (capture_writer.h), but for "color", which the picture writer adds:
// the scene, every render, camera, sensor and ISP setting used, and what was modelled.
#pragma once

#include "integrator/capture/capture.h"
#include "sensor/io/json_writer.h"

namespace camsim {

JsonObject captureSidecar(const CaptureResult& result);

}  // namespace camsim
