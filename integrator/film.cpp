#include "integrator/film.h"

namespace camsim {

Film::Film(glm::ivec2 resolution, const SpectralResponse& response)
    : resolution_(resolution),
      response_(response),
      channels_(static_cast<size_t>(response.channelCount())),
      sums_(static_cast<size_t>(resolution.x) * static_cast<size_t>(resolution.y) * channels_, 0.0) {}

Image Film::toImage(int samplesPerPixel) const {
  std::vector<std::string> names;
  for (int c = 0; c < response_.channelCount(); ++c) names.push_back(response_.channel(c).name);
  Image image(resolution_.x, resolution_.y, names);
  const double scale = samplesPerPixel > 0 ? 1.0 / samplesPerPixel : 0.0;
  for (size_t i = 0; i < sums_.size(); ++i) image.pixels[i] = static_cast<float>(sums_[i] * scale);
  return image;
}

}  // namespace camsim
