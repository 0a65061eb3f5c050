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
  samples_.assign(pixels, 0);
}

void Film::setSpectralReference(const Spectrum& reference) {
  reference_ = reference;
  cvWeights_.clear();
  cvFirst_.clear();
  for (const SpectralResponse* r : responses_) {
    cvFirst_.push_back(cvWeights_.size());
    for (int c = 0; c < r->channelCount(); ++c) {
      const std::array<double, kSpectralBins> w = binIntegrals(r->channel(c).curve, reference);
      SpectralBins& bins = cvWeights_.emplace_back();
      for (int b = 0; b < kSpectralBins; ++b)
        bins[b] = static_cast<float>(w[static_cast<std::size_t>(b)]);
    }
  }
}

namespace {
// sum · (1/n), as the images have always been scaled (the same bits as before).
double meanOf(double sum, int n) {
  return n > 0 ? sum * (1.0 / n) : 0.0;
}
}  // namespace

double Film::errorValue(glm::ivec2 pixel) const {
  const size_t p = index(pixel);
  return meanOf(sums_[p * stride_ + errorOffset_], samples_[p]);
}

double Film::errorOddMean(glm::ivec2 pixel) const {
  const size_t p = index(pixel);
  return meanOf(oddSums_[p], samples_[p] / 2);
}

double Film::errorMean() const {
  double total = 0.0;
  for (size_t p = 0; p < samples_.size(); ++p)
    total += meanOf(sums_[p * stride_ + errorOffset_], samples_[p]);
  return samples_.empty() ? 0.0 : total / static_cast<double>(samples_.size());
}

Image Film::oddHalfImage() const {
  Image image(resolution_.x, resolution_.y, {errorChannelName_});
  for (std::size_t p = 0; p < oddSums_.size(); ++p)
    image.pixels[p] = static_cast<float>(meanOf(oddSums_[p], samples_[p] / 2));
  return image;
}

Image Film::sampleCountImage() const {
  Image image(resolution_.x, resolution_.y, {"spp"});
  for (std::size_t p = 0; p < samples_.size(); ++p)
    image.pixels[p] = static_cast<float>(samples_[p]);
  return image;
}

ErrorMetrics Film::estimateError(int samplesPerPixel) const {
  const std::vector<Image> images = toImages();
  return estimateFromHalves(images[errorImage_], errorImageChannel_, oddHalfImage(),
                            samplesPerPixel);
}

std::vector<Image> Film::toImages() const {
  std::vector<Image> images;
  size_t offset = 0;
  for (const SpectralResponse* r : responses_) {
    const std::vector<std::string> names = r->storedChannelNames();
    Image image(resolution_.x, resolution_.y, names);
    const size_t n = names.size();
    for (size_t p = 0; p < samples_.size(); ++p)
      for (size_t c = 0; c < n; ++c)
        image.pixels[p * n + c] =
            static_cast<float>(meanOf(sums_[p * stride_ + offset + c], samples_[p]));
    offset += n;
    images.push_back(std::move(image));
  }
  return images;
}

}  // namespace camsim
