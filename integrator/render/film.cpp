#include "integrator/render/film.h"

namespace camsim {

Film::Film(glm::ivec2 resolution, std::vector<const SpectralResponse*> responses)
    : resolution_(resolution), responses_(std::move(responses)) {
  for (const SpectralResponse* r : responses_) stride_ += static_cast<size_t>(r->storedChannels());
  sums_.assign(static_cast<size_t>(resolution.x) * static_cast<size_t>(resolution.y) * stride_,
               0.0);
}

std::vector<Image> Film::toImages(int samplesPerPixel) const {
  const double scale = samplesPerPixel > 0 ? 1.0 / samplesPerPixel : 0.0;
  std::vector<Image> images;
  size_t offset = 0;
  for (const SpectralResponse* r : responses_) {
    std::vector<std::string> names;
    if (r->isMosaic())
      names.push_back(r->name());
    else
      for (int c = 0; c < r->channelCount(); ++c) names.push_back(r->channel(c).name);
    Image image(resolution_.x, resolution_.y, names);
    const size_t n = names.size();
    for (size_t p = 0; p < static_cast<size_t>(resolution_.x) * static_cast<size_t>(resolution_.y);
         ++p)
      for (size_t c = 0; c < n; ++c)
        image.pixels[p * n + c] = static_cast<float>(sums_[p * stride_ + offset + c] * scale);
    offset += n;
    images.push_back(std::move(image));
  }
  return images;
}

}  // namespace camsim
