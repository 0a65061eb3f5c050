// PinholeCamera: an ideal pinhole at the camera-space origin, the sensor at the focal
// length behind it. The film records incident radiance (weight 1): a pixel's value is the
// mean radiance over the directions its photosite sees.
//
// | parameter       | unit | default |
// |-----------------|------|---------|
// | sensor width    | m    | 0.036   |
// | sensor height   | m    | 0.024   |
// | resolution      | px   | 640×480 |
// | focal length    | m    | 0.050   |
//
//   film point (x, y) px → sensor point s = ((x/W − ½)·w, (½ − y/H)·h)
//   direction (camera space) = normalize(sₓ, s_y, f)
#pragma once

#include "integrator/camera.h"

namespace camsim {

class PinholeCamera final : public Camera {
 public:
  PinholeCamera(const glm::mat4& worldFromCamera, glm::vec2 sensorSizeM, glm::ivec2 resolution,
                float focalLengthM);

  std::optional<CameraRay> generateRay(const CameraSample& sample) const override;
  glm::ivec2 resolution() const override { return resolution_; }

 private:
  glm::mat4 worldFromCamera_;
  glm::vec2 sensorSize_;
  glm::ivec2 resolution_;
  float focalLength_;
};

}  // namespace camsim
