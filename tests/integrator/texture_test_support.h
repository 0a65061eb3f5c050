// Test support for the texture tests: writing small PNG/EXR files and rendering a textured
// quad inside an emitting sphere (rendered with light_test_support.h's renderLuminance) (a furnace:
// the quad's radiance is ρ(uv)·Lₑ exactly, since the sphere emits Lₑ = 0.01 W·m⁻²·sr⁻¹·nm⁻¹ from
// every direction and reflects nothing).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sensor/io/png_io.h"
#include "sensor/spectra/cie.h"
#include "tests/integrator/render_test_support.h"  // renderLuminance, MaxError

namespace camsim::test {

inline std::filesystem::path writeTestPng(const std::filesystem::path& path, int width, int height,
                                          int channels, int bitDepth,
                                          std::vector<std::uint16_t> samples) {
  PngImage png;
  png.width = width;
  png.height = height;
  png.channels = channels;
  png.bitDepth = bitDepth;
  png.samples = std::move(samples);
  writePng(path, png);
  return path;
}

// Σ ȳ Δλ on the 1 nm grid times Km: the Y (cd/m²) of a flat radiance of 1 W·m⁻²·sr⁻¹·nm⁻¹.
inline double flatRadianceY() {
  return kMaxLuminousEfficacy * Cie1931::get().y.sum();
}

// An 8×8 pinhole view from the origin along +z of the square x, y ∈ [−1, 1] at z = 1
// (square 36 mm sensor, 18 mm lens), filled by a rectangle with uv (0, 0) at the image's
// bottom-left and (1, 1) at its top-right (the camera's right is −x): pixel (px, py), row 0
// at the top, sees uv ∈ [px/8, (px+1)/8] × [1 − (py+1)/8, 1 − py/8]. `reflectance` is the
// YAML of the quad's reflectance.
inline std::string texturedQuadScene(const std::string& reflectance) {
  return "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [8, 8], focal_length_mm: "
         "18,\n"
         "         sensor_width_mm: 36, sensor_height_mm: 36}\n"
         "render: {max_depth: 4}\n"
         "materials: {quad: {type: diffuse, reflectance: " +
         reflectance +
         "}}\n"
         "shapes:\n"
         "  - {type: rectangle, corner: [1, -1, 1], edge_u: [-2, 0, 0], edge_v: [0, 2, 0], "
         "material: quad}\n"
         "  - {type: sphere, centre: [0, 0, 0.5], radius: 3, emission: {scale: 0.01, spectrum: 1, "
         "two_sided: true}}\n";
}

}  // namespace camsim::test
