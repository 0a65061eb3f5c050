#include "integrator/pinhole_camera.h"

#include <glm/geometric.hpp>

namespace camsim {

PinholeCamera::PinholeCamera(const glm::mat4& worldFromCamera, glm::vec2 sensorSizeM,
                             glm::ivec2 resolution, float focalLengthM)
    : worldFromCamera_(worldFromCamera),
      sensorSize_(sensorSizeM),
      resolution_(resolution),
      focalLength_(focalLengthM) {}

std::optional<CameraRay> PinholeCamera::generateRay(const CameraSample& sample) const {
  const glm::vec2 ndc = sample.pFilm / glm::vec2(resolution_);
  const glm::vec3 dirCamera((ndc.x - 0.5f) * sensorSize_.x, (0.5f - ndc.y) * sensorSize_.y,
                            focalLength_);
  CameraRay cr;
  cr.ray.o = glm::vec3(worldFromCamera_[3]);
  cr.ray.d = glm::normalize(glm::vec3(worldFromCamera_ * glm::vec4(dirCamera, 0.0f)));
  cr.ray.time = sample.time;
  return cr;
}

}  // namespace camsim
