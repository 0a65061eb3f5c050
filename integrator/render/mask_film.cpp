#include "integrator/render/mask_film.h"

#include <algorithm>

#include "sensor/base/check.h"

namespace camsim {

MaskFilm::MaskFilm(const Scene& scene) : crossings_(*scene.labelledGeometry()) {
  slotOfShape_.assign(scene.shapeCount(), -1);
  const IdTable& classes = scene.ids()[IdKind::kClass];
  for (std::size_t s = 0; s < scene.shapeCount(); ++s) {
    if (classes.ofShape[s] == 0) continue;  // unlabelled: background
    slotOfShape_[s] = static_cast<int>(shapes_.size());
    shapes_.push_back(static_cast<int>(s));
  }
}

std::vector<std::string> MaskFilm::channels() const {
  std::vector<std::string> c;
  for (const char* kind : {"amodal_", "visible_"})
    for (int s : shapes_) c.push_back(kind + std::to_string(s + 1) + ".A");
  return c;
}

void MaskFilm::clear(Counts& c) {
  std::fill(c.amodal.begin(), c.amodal.end(), 0u);
  std::fill(c.visible.begin(), c.visible.end(), 0u);
}

void MaskFilm::add(Counts& c, const Ray* cameraRay, int firstHitShape) const {
  if (!cameraRay) return;
  if (firstHitShape >= 0) {
    const int slot = slotOfShape_[static_cast<std::size_t>(firstHitShape)];
    if (slot >= 0) ++c.visible[static_cast<std::size_t>(slot)];
  }
  std::array<int, kMaxCrossings> crossed;
  const int n = std::min(crossings_.crossedShapes(*cameraRay, crossed), kMaxCrossings);
  for (int i = 0; i < n; ++i) {
    const int slot = slotOfShape_[static_cast<std::size_t>(crossed[static_cast<std::size_t>(i)])];
    CAMSIM_CHECK(slot >= 0);  // the crossings scene holds the labelled shapes only
    ++c.amodal[static_cast<std::size_t>(slot)];
  }
}

void MaskFilm::write(const Counts& c, int samplesPerPixel, float* out) const {
  const double inv = 1.0 / samplesPerPixel;
  const std::size_t n = shapes_.size();
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = static_cast<float>(c.amodal[i] * inv);
    out[n + i] = static_cast<float>(c.visible[i] * inv);
  }
}

}  // namespace camsim
