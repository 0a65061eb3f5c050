#include "integrator/render/film.h"

namespace camsim {

Film::Film(glm::ivec2 resolution, std::vector<const SpectralResponse*> responses)
    : resolution_(resolution), responses_(std::move(responses)) {
  // The error channel: the first "Y" of a response that is not a mosaic, else offset 0.
  for (std::size_t k = 0; k < responses_.size(); ++k) {
    const SpectralResponse* r = responses_[k];
    if (!r->isMosaic())
      for (int c = 0; c < r->channelCount() && errorChannelName_.empty(); ++c)
        if (r->channel(c).name == "Y") {
          errorOffset_ = stride_ + static_cast<size_t>(c);
          errorImage_ = k;
          errorImageChannel_ = c;
          errorChannelName_ = "Y";
        }
    stride_ += static_cast<size_t>(r->storedChannels());
  }
  if (errorChannelName_.empty() && !responses_.empty()) {
    const SpectralResponse& first = *responses_.front();
    errorChannelName_ = first.isMosaic() ? first.name() : first.channel(0).name;
  }
  const size_t pixels = static_cast<size_t>(resolution.x) * static_cast<size_t>(resolution.y);
  sums_.assign(pixels * stride_, 0.0);
  oddSums_.assign(pixels, 0.0);
}

Image Film::oddHalfImage(int samplesPerPixel) const {
  Image image(resolution_.x, resolution_.y, {errorChannelName_});
  const double scale = samplesPerPixel >= 2 ? 1.0 / (samplesPerPixel / 2) : 0.0;
  for (std::size_t p = 0; p < oddSums_.size(); ++p)
    image.pixels[p] = static_cast<float>(oddSums_[p] * scale);
  return image;
}

ErrorMetrics Film::estimateError(int samplesPerPixel) const {
  const std::vector<Image> images = toImages(samplesPerPixel);
  return estimateFromHalves(images[errorImage_], errorImageChannel_, oddHalfImage(samplesPerPixel),
                            samplesPerPixel);
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
