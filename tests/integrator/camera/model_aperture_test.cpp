// Depth of field through the camera models (issue 36; docs/camera.md, "Aperture, motion,
// rolling shutter"): with an aperture and a focus distance z_o, every ray from one film
// point passes through one point — for opencv the chief ray's point on the plane z = z_o,
// for every other model the chief ray's point at distance z_o from the centre (a sphere of
// focus) — and it starts on the stop: in the lens plane for opencv, on the disc of radius
// D/2 facing the chief ray for the others. The weight does not depend on the lens point.
// Checked for film points across each model's image, including > 90° off axis, against
// the geometry stated here (the ray misses the point of focus by < 1e-6 z_o: its float direction; weights to 1e-6), not the library's own functions.
// Diffraction is off: it would move the film point (diffraction_test.cpp tests it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/scene/scene_loader.h"

namespace camsim::model_aperture_test {
namespace {

PhysicalCamera cameraWith(const std::string& projection) {
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [64, 64], "
      "sensor_width_mm: 3.2, sensor_height_mm: 3.2, focal_length_mm: 1, f_number: 2, "
      "focus_distance_m: 0.8, aperture: {blades: 0, diffraction: false}, projection: " +
      projection +
      "}\nshapes: [{type: sphere, centre: [0, 0, 5], radius: 1, emission: {luminance: 1}}]\n";
  return PhysicalCamera(loadSceneFromText(yaml, "aperture.yaml", ".").camera);
}

TEST(ModelAperture, RaysFromAFilmPointMeetOnTheSurfaceOfFocus) {
  struct Case {
    const char* projection;
    bool plane;  // opencv: plane of focus z = z_o; else a sphere of radius z_o
  };
  const Case cases[] = {
      {"{model: opencv, k1: -0.2, k2: 0.03}", true},
      {"{model: equidistant, max_field_angle_deg: 100}", false},
      {"{model: kannala_brandt, k1: 0.02, k2: -0.003, max_field_angle_deg: 100}", false},
      {"{model: double_sphere, xi: -0.2, alpha: 0.6, max_field_angle_deg: 100}", false},
      {"{model: equirectangular}", false}};
  const double zo = 0.8, radius = 0.25e-3;  // D/2 = f/(2N)
  const SampledWavelengths lambda = SampledWavelengths::sampleVisible(0.3f);
  for (const Case& c : cases) {
    const PhysicalCamera camera = cameraWith(c.projection);
    int films = 0;
    double widest = 0.0;
    for (int fy = 2; fy < 64; fy += 6)
      for (int fx = 2; fx < 64; fx += 6) {
        CameraSample s;
        s.pFilm = {fx + 0.25f, fy + 0.75f};
        s.pLens = {0.5f, 0.5f};  // the stop's centre: the chief ray
        const std::optional<CameraRay> chief = camera.generateRay(s, lambda);
        if (!chief) continue;
        const glm::dvec3 d = glm::normalize(glm::dvec3(chief->ray.d));
        ASSERT_NEAR(glm::length(glm::dvec3(chief->ray.o)), 0.0, 1e-12) << c.projection;
        widest = std::max(widest, std::acos(d.z));
        const glm::dvec3 focus = c.plane ? d * (zo / d.z) : d * zo;
        ++films;
        for (float u : {0.1f, 0.45f, 0.9f})
          for (float v : {0.05f, 0.6f, 0.95f}) {
            s.pLens = {u, v};
            const std::optional<CameraRay> r = camera.generateRay(s, lambda);
            ASSERT_TRUE(r) << c.projection;
            const glm::dvec3 o(r->ray.o), dir = glm::normalize(glm::dvec3(r->ray.d));
            // On the stop: within D/2 of the centre, in the lens plane or facing the chief ray.
            EXPECT_LE(glm::length(o), radius * (1.0 + 1e-6)) << c.projection;
            EXPECT_NEAR(c.plane ? o.z : glm::dot(o, d), 0.0, 1e-9) << c.projection;
            // Through the point of focus: its distance from the ray.
            const glm::dvec3 toFocus = focus - o;
            const double miss = glm::length(toFocus - glm::dot(toFocus, dir) * dir);
            EXPECT_LT(miss, 1e-6 * zo) << c.projection << " film " << fx << "," << fy;
            EXPECT_NEAR(r->weight[0] / chief->weight[0], 1.0, 1e-6) << c.projection;
          }
      }
    std::printf("[measured] %s: %d film points up to %.1f deg off axis\n", c.projection, films,
                widest * 180.0 / M_PI);
    EXPECT_GE(films, 40) << c.projection;
  }
}

}  // namespace
}  // namespace camsim::model_aperture_test
