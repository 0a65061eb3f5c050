// Ground-truth outputs (integrator/render/aov_film.h) against closed forms: depth, distance,
// position and normals of a fronto-parallel plane, a tilted plane and a sphere seen through
// a pinhole; albedo and roughness as the scene gives them; the same bytes for any thread
// count; and the image unchanged by asking for them.
#include "integrator/render/aov_film.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "tests/support/scene_text.h"

namespace camsim {
namespace {

using test::num;

constexpr int kRes = 32;
constexpr double kAovFocal = 0.02, kSensor = 0.024;  // pinhole: 24 mm film, 20 mm image distance
constexpr const char* kAllAovs = "[depth, distance, position, normal, albedo, roughness]";

RenderResult renderAovs(const std::string& shapes, const std::string& materials,
                        const std::string& aovs = kAllAovs, int threads = 0,
                        const std::string& camera = "position: [0, 0, 0], look_at: [0, 0, 100]") {
  const std::string text = "camera: {" + camera + ", up: [0, 1, 0], resolution: [" +
                           std::to_string(kRes) + ", " + std::to_string(kRes) +
                           "], sensor_width_mm: 24, sensor_height_mm: 24, focal_length_mm: 20}\n"
                           "render: {spp: 64, max_depth: 1, aovs: " +
                           aovs + "}\nmaterials: {" + materials + "}\nshapes:\n" + shapes +
                           "lights:\n  - {type: point, position: [0, 0, 0], intensity: 1}\n";
  const SceneDescription d = loadSceneFromText(text, "aov.yaml", ".");
  RenderOptions o;
  o.spp = d.render.spp;
  o.threads = threads;
  return render(Scene(d), SpectralResponse::cieXyz(), o);
}

// The film point of pixel (x + fx, y + fy) in camera axes (x right, y up), m. Looking
// along +z with +y up, the camera's right is world −x.
glm::dvec2 filmPoint(double x, double y) {
  const double pitch = kSensor / kRes;
  return {(x - 0.5 * kRes) * pitch, (0.5 * kRes - y) * pitch};
}

// The pixel mean of f(ray direction d, |d_z| = 1) over its box footprint, on a 16×16 grid.
template <typename F>
double footprintMean(int x, int y, F f) {
  double sum = 0.0;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      const glm::dvec2 s = filmPoint(x + (i + 0.5) / 16.0, y + (j + 0.5) / 16.0);
      // A pinhole images film point s through the centre: the ray towards (−s, f), i.e.
      // the scene point seen at pixel (x, y) lies along (s.x, s.y, f) in the upright image.
      sum += f(glm::dvec3(s.x / kAovFocal, s.y / kAovFocal, 1.0));
    }
  return sum / 256.0;
}

float at(const Image& im, int x, int y, const char* channel) {
  return im.at(x, y, im.channelIndex(channel));
}

// A plane z = 2 m facing the camera: depth exactly 2 everywhere (no averaging changes a
// constant), distance the footprint mean of 2·|d|, position linear in the film point (its
// mean is the centre's, up to the 64 samples' stratification: 1/64 px), normals exact.
TEST(Aovs, FrontoParallelPlane) {
  const RenderResult r = renderAovs(
      "  - {type: rectangle, corner: [-5, -5, 2], edge_u: [0, 10, 0], edge_v: [10, 0, 0], "
      "material: grey}\n",
      "grey: {type: diffuse, reflectance: 0.5}");
  const Image& a = r.aovs;
  ASSERT_EQ(a.width, kRes);
  const double pitchAt2m = 2.0 * kSensor / kRes / kAovFocal;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      ASSERT_EQ(at(a, x, y, "coverage.A"), 1.0f);
      EXPECT_FLOAT_EQ(at(a, x, y, "depth.Z"), 2.0f) << x << "," << y;
      const double dist = footprintMean(x, y, [](glm::dvec3 d) { return 2.0 * glm::length(d); });
      EXPECT_NEAR(at(a, x, y, "distance.Z"), dist, 2e-4 * dist) << x << "," << y;
      const glm::dvec2 c = filmPoint(x + 0.5, y + 0.5) * (2.0 / kAovFocal);
      EXPECT_NEAR(at(a, x, y, "P.X"), -c.x, pitchAt2m / 64.0) << x << "," << y;  // right = −x
      EXPECT_NEAR(at(a, x, y, "P.Y"), c.y, pitchAt2m / 64.0) << x << "," << y;
      EXPECT_FLOAT_EQ(at(a, x, y, "P.Z"), 2.0f);
      // The rectangle's front is edge_u × edge_v = −z: towards the camera.
      EXPECT_EQ(at(a, x, y, "Ng.Z"), -1.0f);
      EXPECT_EQ(at(a, x, y, "N.Z"), -1.0f);
      EXPECT_EQ(at(a, x, y, "Ng_cam.Z"), -1.0f);  // OpenCV axes: z forward
      EXPECT_EQ(at(a, x, y, "Ng_cam.X"), 0.0f);
      EXPECT_NEAR(at(a, x, y, "albedo.R"), 0.5f, 1e-6f);
      EXPECT_NEAR(at(a, x, y, "albedo.G"), 0.5f, 1e-6f);
      EXPECT_NEAR(at(a, x, y, "albedo.B"), 0.5f, 1e-6f);
      EXPECT_EQ(at(a, x, y, "roughness.Y"), 1.0f);
    }
}

// A plane through (0, 0, 2) turned 30° about +y: depth z = 2 + x_world tan 30° along each
// ray, i.e. z(d) = 2 / (1 + d.x tan 30°) with d in camera axes (x_world = −x_camera); its pixel mean against the footprint's, within 1/64 of the
// depth's change across the pixel. The normal in camera axes (OpenCV, y down) is exact.
TEST(Aovs, TiltedPlaneDepthIsTheFootprintMean) {
  const double t = std::tan(M_PI / 6.0), c = std::cos(M_PI / 6.0), s = std::sin(M_PI / 6.0);
  const std::string shapes = "  - {type: rectangle, corner: [" + num(-3 * c) + ", -3, " +
                             num(2 - 3 * s) + "], edge_u: [0, 6, 0], edge_v: [" + num(6 * c) +
                             ", 0, " + num(6 * s) + "], material: m}\n";
  const RenderResult r = renderAovs(shapes, "m: {type: plastic, reflectance: 0.3, roughness: 0.2}",
                                    "[depth, normal, roughness]");
  const Image& a = r.aovs;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      const auto z = [t](glm::dvec3 d) { return 2.0 / (1.0 + d.x * t); };
      const double mean = footprintMean(x, y, z);
      const double change = std::abs(z(glm::dvec3(filmPoint(x + 1, y) / kAovFocal, 1.0)) -
                                     z(glm::dvec3(filmPoint(x, y) / kAovFocal, 1.0)));
      EXPECT_NEAR(at(a, x, y, "depth.Z"), mean, change / 64.0 + 1e-6) << x << "," << y;
      // Front = edge_u × edge_v ∝ (s, 0, −c) in world axes: (−s, 0, −c) in camera axes.
      EXPECT_NEAR(at(a, x, y, "Ng_cam.X"), -s, 1e-6);
      EXPECT_NEAR(at(a, x, y, "Ng_cam.Y"), 0.0, 1e-6);
      EXPECT_NEAR(at(a, x, y, "Ng_cam.Z"), -c, 1e-6);
      EXPECT_FLOAT_EQ(at(a, x, y, "roughness.Y"), 0.2f);
    }
}

// A sphere of radius 1 m at (0, 0, 4): in every pixel that it covers fully, the position
// and normal are the footprint means of the ray–sphere hit and of its normal (each pixel
// spans 0.15 m there, so the mean point lies inside the sphere near the limb), within 1/64
// of their change across the pixel; the edge pixels' coverage is fractional; pixels beside
// it are empty.
TEST(Aovs, SphereFootprintMeans) {
  const RenderResult r =
      renderAovs("  - {type: sphere, centre: [0, 0, 4], radius: 1, material: m}\n",
                 "m: {type: mirror, reflectance: 0.9}", "[position, normal, albedo, roughness]");
  const Image& a = r.aovs;
  const glm::dvec3 centre(0, 0, 4);
  // The hit of the ray along camera direction d (world x = −camera x); t < 0: a miss.
  const auto hit = [&](glm::dvec3 d) {
    const glm::dvec3 w = glm::normalize(glm::dvec3(-d.x, d.y, d.z));
    const double b = glm::dot(w, centre), disc = b * b - (glm::dot(centre, centre) - 1.0);
    return disc < 0.0 ? glm::dvec3(0.0) : w * (b - std::sqrt(disc));
  };
  const double pitch = 4.0 * kSensor / kRes / kAovFocal;
  int full = 0, partial = 0, empty = 0;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      const float cov = at(a, x, y, "coverage.A");
      if (cov == 0.0f) {
        ++empty;
        EXPECT_EQ(at(a, x, y, "P.Z"), 0.0f);
        continue;
      }
      bool allHit = true;
      footprintMean(x, y, [&](glm::dvec3 d) { return allHit &= hit(d).z > 0.0, 0.0; });
      if (cov < 1.0f || !allHit) {
        partial += cov < 1.0f;
        continue;
      }
      ++full;
      for (int i = 0; i < 3; ++i) {
        const char* pc[] = {"P.X", "P.Y", "P.Z"};
        const char* nc[] = {"N.X", "N.Y", "N.Z"};
        const double p = footprintMean(x, y, [&](glm::dvec3 d) { return hit(d)[i]; });
        const double n = footprintMean(x, y, [&](glm::dvec3 d) { return (hit(d) - centre)[i]; });
        EXPECT_NEAR(at(a, x, y, pc[i]), p, pitch / 64.0 + 1e-5) << x << "," << y;
        EXPECT_NEAR(at(a, x, y, nc[i]), n, pitch / 64.0 + 1e-5) << x << "," << y;
      }
      EXPECT_NEAR(at(a, x, y, "albedo.G"), 0.9f, 1e-6f);
      EXPECT_EQ(at(a, x, y, "roughness.Y"), 0.0f);
    }
  EXPECT_GT(full, 20);
  EXPECT_GT(partial, 10);
  EXPECT_GT(empty, 100);
}

// Far from the origin, P holds world coordinates (render space + origin, summed in double).
TEST(Aovs, PositionIsInWorldCoordinates) {
  const RenderResult r = renderAovs(
      "  - {type: rectangle, corner: [999995, -5, 2], edge_u: [0, 10, 0], edge_v: [10, 0, 0], "
      "material: grey}\n",
      "grey: {type: diffuse, reflectance: 0.5}", "[position, depth]", 0,
      "position: [1000000, 0, 0], look_at: [1000000, 0, 100]");
  EXPECT_NEAR(at(r.aovs, 16, 16, "P.X"), 1000000.0 - 0.5 * 2.0 * kSensor / kRes / kAovFocal, 0.07);
  EXPECT_FLOAT_EQ(at(r.aovs, 16, 16, "depth.Z"), 2.0f);
}

// The same bytes for any thread count, and the image is the image without AOVs.
TEST(Aovs, DeterministicAndTheImageUnchanged) {
  const std::string shapes =
      "  - {type: sphere, centre: [0.3, 0, 4], radius: 1, material: m}\n"
      "  - {type: rectangle, corner: [-5, -5, 6], edge_u: [0, 10, 0], edge_v: [10, 0, 0], "
      "material: m}\n";
  const std::string materials = "m: {type: diffuse, reflectance: {rgb: [0.63, 0.065, 0.05]}}";
  const RenderResult one = renderAovs(shapes, materials, kAllAovs, 1);
  const RenderResult two = renderAovs(shapes, materials, kAllAovs, 2);
  const RenderResult none = renderAovs(shapes, materials, "[]", 2);
  EXPECT_EQ(one.aovs.pixels, two.aovs.pixels);
  EXPECT_EQ(one.image.pixels, two.image.pixels);
  EXPECT_EQ(one.image.pixels, none.image.pixels);
  EXPECT_TRUE(none.aovs.pixels.empty());
  // The uplifted red reads back as its RGB (the uplift's fit, within 0.01).
  EXPECT_NEAR(at(one.aovs, 16, 16, "albedo.R"), 0.63f, 0.01f);
  EXPECT_NEAR(at(one.aovs, 16, 16, "albedo.G"), 0.065f, 0.01f);
  EXPECT_NEAR(at(one.aovs, 16, 16, "albedo.B"), 0.05f, 0.01f);
}

}  // namespace
}  // namespace camsim
