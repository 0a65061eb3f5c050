// Per-frame instance annotations for the dataset metadata (dataset_writer.h): for each
// visible instance whose shape has a `class:` (unlabelled shapes are background and are
// left out), its pixels — where it is the dominant id of the instance_id AOV — as a tight
// box and a COCO run-length mask, and the box of its projected 3-D bounds.
//
// | field        | unit | convention |
// |--------------|------|------------|
// | bbox         | px   | COCO [x, y, width, height] of the pixels, x, y of the top-left pixel's corner (the image's corner is 0, 0) |
// | bbox_3d      | px   | the same corner convention: the 2-D bounds of the 8 projected corners of the shape's world-axis box at the frame's reference time (unclipped; none if a corner is behind the lens) |
// | area         | px   | the number of pixels |
// | segmentation | —    | COCO uncompressed RLE: counts of alternating 0 and 1 runs (0 first) down the columns, left to right; size [height, width] |
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "integrator/capture/capture.h"

namespace camsim {

struct InstanceAnnotation {
  std::uint32_t instance = 0;  // the instance's dominant-id number (scene_ids.h)
  std::string name;            // the shape's name
  std::uint32_t category = 0;  // its class number
  std::string categoryName;
  std::uint64_t area = 0;
  glm::dvec4 bbox{0.0};              // x, y, w, h
  std::optional<glm::dvec4> bbox3d;  // x, y, w, h
  std::vector<std::uint64_t> rle;    // COCO counts
};

// The annotations of a frame rendered with the instance_id AOV (none without it).
std::vector<InstanceAnnotation> annotateFrame(const CaptureResult& result);

}  // namespace camsim
