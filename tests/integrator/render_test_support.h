// Test helpers for tests that render: render a scene given as YAML text and return each
// pixel's mean radiance-weighted luminance Y (cd/m²), i.e. the film divided by the exact
// mean pinhole weight (tests/integrator/camera_weight.h), so that pixels compare directly
// with radiance closed forms; and small scene fragments.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/spectra/cie.h"
#include "tests/integrator/camera_weight.h"

namespace camsim::test {

// The largest relative error |value/expected − 1| seen by a test, recorded as the test
// property "max_relative_error" (visible with --gtest_output=xml) when it goes out of
// scope; the measured values quoted next to the tolerances come from it.
class MaxError {
 public:
  MaxError() = default;
  MaxError(const MaxError&) = delete;
  MaxError& operator=(const MaxError&) = delete;
  ~MaxError() {
    char text[32];
    std::snprintf(text, sizeof text, "%.2e", max_);
    ::testing::Test::RecordProperty("max_relative_error", text);
  }
  double operator()(double value, double expected) {
    const double e = std::abs(value / expected - 1.0);
    max_ = std::max(max_, std::isnan(e) ? 1e300 : e);
    return e;
  }

 private:
  double max_ = 0.0;
};

// Y (cd/m²) of a flat spectral radiance of 1 W·m⁻²·sr⁻¹·nm⁻¹.
inline double flatY() {
  return kMaxLuminousEfficacy * Cie1931::get().y.sum();
}

struct LuminanceImage {
  Image y;  // one channel: mean luminance of the pixel's footprint, cd/m²
  RenderStats stats;
  double at(int x, int yy) const { return static_cast<double>(y.at(x, yy, 0)); }
};

// The mean of Y over the image.
inline double meanOf(const LuminanceImage& img) {
  double sum = 0.0;
  for (int y = 0; y < img.y.height; ++y)
    for (int x = 0; x < img.y.width; ++x) sum += img.at(x, y);
  return sum / (img.y.width * img.y.height);
}

inline LuminanceImage renderLuminance(const std::string& yaml, int spp, std::uint64_t seed = 1,
                                      const std::filesystem::path& baseDir = ".") {
  const SceneDescription desc = loadSceneFromText(yaml, "test.yaml", baseDir);
  const Scene scene(desc);
  RenderOptions options;
  options.spp = spp;
  options.seed = seed;
  options.threads = 2;
  const SpectralResponse response = SpectralResponse::cieXyz();
  const RenderResult result = render(scene, response, options);
  const Image& img = result.image;
  const int yc = img.channelIndex("Y");
  LuminanceImage out{Image(img.width, img.height, {"Y"}), result.stats};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      out.y.at(x, y, 0) = static_cast<float>(static_cast<double>(img.at(x, y, yc)) /
                                             meanPinholeWeight(scene.camera(), x, y));
  return out;
}

// A camera 1 m above the origin looking straight down (−y) with a 1 mm sensor and a
// 50 mm lens: the footprint of the whole image on the floor is 2 cm wide, so cos θ / d²
// of a light ≈ 1 m away varies by < 10⁻³ over it.
inline std::string cameraAboveOrigin(int resolution) {
  const std::string r = std::to_string(resolution);
  return "camera: {position: [0, 1, 0], look_at: [0, 0, 0], up: [0, 0, 1], sensor_width_mm: 1,\n"
         "         sensor_height_mm: 1, focal_length_mm: 50, resolution: [" +
         r + ", " + r + "]}\n";
}

// The cos⁴-weighted mean over pixel (px, py) of an n × n cameraAboveOrigin image of a
// function of the floor point it sees (the pixel's expectation; 16 × 16 points). The
// camera looks down −y with up +z, so image right is −x and image down is −z; the image
// spans 2 cm × 2 cm of floor.
template <typename F>
double footprintMean(int n, int px, int py, F f) {
  constexpr int kSub = 16;
  double sum = 0.0, weights = 0.0;
  for (int j = 0; j < kSub; ++j)
    for (int i = 0; i < kSub; ++i) {
      const double a = ((px + (i + 0.5) / kSub) / n - 0.5) * 0.02;  // m on the floor
      const double b = ((py + (j + 0.5) / kSub) / n - 0.5) * 0.02;
      const double cos2 = 1.0 / (1.0 + a * a + b * b);  // camera 1 m above the floor
      sum += cos2 * cos2 * f(-a, -b);
      weights += cos2 * cos2;
    }
  return sum / weights;
}

// A 20 m × 20 m floor in the plane y = 0, front side up (+y), of reflectance rho.
inline std::string floorOf(double rho) {
  return "materials: {floor: {type: diffuse, reflectance: " + std::to_string(rho) +
         "}}\n"
         "shapes:\n"
         "  - {type: rectangle, corner: [-10, 0, -10], edge_u: [0, 0, 20], edge_v: [20, 0, 0],\n"
         "     material: floor}\n";
}

}  // namespace camsim::test
