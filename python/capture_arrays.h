// A capture's result as Python sees it: the CaptureResult (moved, never copied) and the few
// images derived from it the way the CLI's writers derive them, in one shared owner; and the
// dict of NumPy arrays that view those buffers. Each array holds the owner through its
// capsule (its `base`), so the buffers live as long as any array or the dict does.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "integrator/capture/capture.h"
#include "sensor/io/picture_writer.h"

namespace camsim::python {

struct CaptureBuffers {
  CaptureResult result;
  Image filmExr;  // xyzExrImage(film): R, G, B (linear Rec.709) then XYZ, NAME.exr's values
  Image display;  // result.picture through OCIO: display-encoded RGB
  std::vector<std::uint8_t> display8;  // quantizeDisplay8(display): NAME.png's bytes
  DisplayChoice choice;                // the resolved display, view and look
  std::string ocioConfig;              // the config file used
  std::vector<std::string> idLayers;   // the aovs' KIND.id channels, converted to uint32 below
  std::vector<std::vector<std::uint32_t>> ids;
  std::string sidecarJson;  // captureSidecar(result): NAME.json but for "color"
  std::string posesJson;    // the frame's pose and intrinsics (dataset_writer.h conventions)
};

// Fills everything but result from result (no Python: runs on the render's worker thread).
void deriveBuffers(CaptureBuffers& b, const PictureSettings& picture);

// The dict of arrays and meta (with the GIL held).
pybind11::dict captureDict(const std::shared_ptr<CaptureBuffers>& b);

}  // namespace camsim::python
