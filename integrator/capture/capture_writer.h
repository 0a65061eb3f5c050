// writeCapture(): everything a capture (capture.h) produced, written into one directory
// through one OutputSet — all files appear at once under their final names, or none:
//
//   NAME.exr              the film: R, G, B (linear Rec.709) and XYZ.X/Y/Z, absolute
//                         (lm·s per photosite), camera intrinsics in the header
//   NAME[_evX].dng        with a mosaic sensor, per frame: raw DN, colour matrices fitted
//                         from the QE, AsShotNeutral = 1/g of the frame's white balance
//   NAME[_evX]_raw.exr    per frame: raw DN and the expected electrons (a stacked sensor:
//                         NAME[_evX]_raw_<channel>.exr per plane, no DNG)
//   NAME_acescg.exr       with a sensor: the developed scene-linear ACEScg image
//   NAME.png              the picture through OpenColorIO's display/view/look
//   NAME.json             every setting used, the modelled dimensions, the ISP's matrices
//   NAME_<layer>.png      with aovPreviews: false-colour quick looks of the AOVs
//   bop/                  with `exports: [bop]` and no `frames` block: the capture as
//                         image 0 of a BOP scene (bop_writer.h; a sequence's is written
//                         by CaptureRunWriter, capture_run.h)
// A cancelled capture writes only NAME.partial.exr with the tiles that finished (nothing
// when none had), never a final name. docs/output.md lists every key.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "integrator/capture/capture.h"
#include "sensor/io/picture_writer.h"

namespace camsim {

struct CaptureOutputOptions {
  std::filesystem::path directory;  // created if missing
  PictureSettings picture;          // OCIO config and display/view/look of NAME.png
  bool aovPreviews = false;         // also NAME_<layer>.png quick looks (aov_previews.h)
  // Same scene, seed and build → the same bytes in every file: the render's wall time
  // (camsim:render_seconds, render.seconds) is left out. Datasets and tile merges set it.
  bool reproducible = false;
  // The dataset item's index (0 for a render): the BOP export's scene id (bop_writer.h) and a
  // single capture's KITTI image id (kitti_writer.h), so items' exports merge by copying.
  int datasetItem = 0;
};

struct WrittenCapture {
  std::vector<std::filesystem::path> files;    // final names
  std::vector<std::filesystem::path> removed;  // a NAME.partial.exr an interrupted run left
  std::vector<std::string> skipped{};  // exports (or parts) left out, a line each with the reason
};

class PoseModels;  // bop_writer.h

// Throws InputError (nothing is written then) when a file cannot be written. models: the
// run's pose-export models (PoseModels of result.description, made once per run before it
// renders: CaptureRunWriter's, a dataset item's); null (a capture written alone: a merge,
// a test): made here, before any file is written (which checks that the BOP and KITTI
// exports can be written).
WrittenCapture writeCapture(const CaptureResult& result, const CaptureOutputOptions& options,
                            const PoseModels* models = nullptr);

// The file frame i is written as (its DNG, else its raw EXR): for messages.
std::string captureFrameFile(const CaptureResult& result, std::size_t frame);

// The scene-linear NAME.exr image: R, G, B (linear Rec.709) and the XYZ layer, absolute.
Image xyzExrImage(const Image& xyz);

}  // namespace camsim
