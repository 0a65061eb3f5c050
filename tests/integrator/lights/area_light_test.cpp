// Tests for integrator/lights/area_light.cpp: a one-sided quad lamp gives no light samples to points
// behind it, without sampling a point on it (the early rejection by its front plane), and
// the full radiance, with the solid-angle pdf of uniform area sampling, to points in front;
// a two-sided lamp lights both sides.
#include "integrator/lights/area_light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "integrator/geometry/triangle_mesh.h"

namespace camsim {
namespace {

// A 1 m × 1 m lamp in the plane y = 2, facing down (−y), centred above the origin.
TriangleMesh lampFacingDown() {
  return TriangleMesh({{-0.5f, 2, -0.5f}, {0.5f, 2, -0.5f}, {0.5f, 2, 0.5f}, {-0.5f, 2, 0.5f}}, {},
                      {0, 1, 2, 0, 2, 3}, TimeSteps{});
}

// A shape that forwards to a mesh and counts the points sampled on it.
class CountingShape final : public Shape {
 public:
  explicit CountingShape(const TriangleMesh& mesh) : mesh_(mesh) {}
  float area() const override { return mesh_.area(); }
  const TimeSteps& timeSteps() const override { return mesh_.timeSteps(); }
  const InstanceMotion& instanceMotion() const override { return mesh_.instanceMotion(); }
  SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const override {
    return mesh_.interaction(hit, ray);
  }
  std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2,
                                    double time) const override {
    ++samples;
    return mesh_.sample(ref, u1, u2, time);
  }
  float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const override {
    return mesh_.pdf(ref, onShape);
  }
  std::optional<FrontPlane> frontPlane() const override { return mesh_.frontPlane(); }
  mutable int samples = 0;

 private:
  const TriangleMesh& mesh_;
};

int samplesFrom(const AreaLight& light, const glm::vec3& ref, const SampledWavelengths& lambda) {
  int count = 0;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const float u = (static_cast<float>(i) + 0.5f) / 16.0f;
      const float v = (static_cast<float>(j) + 0.5f) / 16.0f;
      if (light.sample(ref, 0.0f, u, {v, u}, lambda)) ++count;
    }
  return count;
}

TEST(AreaLight, OneSidedLampLightsOnlyItsFrontSide) {
  const TriangleMesh mesh = lampFacingDown();
  ASSERT_TRUE(mesh.frontPlane());
  ASSERT_LT(mesh.frontPlane()->n.y, -0.999f);
  const AreaLight light(mesh, Spectrum::constant(2.0), /*twoSided=*/false);
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.3f);
  EXPECT_EQ(samplesFrom(light, {0.2f, 0.0f, 0.1f}, lambda), 256);  // below: in front
  EXPECT_EQ(samplesFrom(light, {0.2f, 3.0f, 0.1f}, lambda), 0);    // above: behind
  EXPECT_EQ(samplesFrom(light, {9.0f, 2.5f, -4.0f}, lambda), 0);   // behind, off to a side

  // In front: L is the radiance and pdf = d² / (A cos θ) for the sampled point.
  const glm::vec3 ref(0.2f, 0.0f, 0.1f);
  const std::optional<LightSample> ls = light.sample(ref, 0.0f, 0.3f, {0.6f, 0.2f}, lambda);
  ASSERT_TRUE(ls);
  EXPECT_FLOAT_EQ(ls->L[0], 2.0f);
  const glm::vec3 d = ls->point.p - ref;
  const float dist2 = glm::dot(d, d);
  const float cosTheta = d.y / std::sqrt(dist2);
  EXPECT_NEAR(ls->pdf, dist2 / cosTheta, 1e-5f * ls->pdf);
}

// The early rejection: behind the lamp no point on it is even sampled.
TEST(AreaLight, PointsBehindAOneSidedLampSampleNothing) {
  const TriangleMesh mesh = lampFacingDown();
  const CountingShape counting(mesh);
  const AreaLight oneSided(counting, Spectrum::constant(2.0), /*twoSided=*/false);
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.3f);
  EXPECT_EQ(samplesFrom(oneSided, {0.2f, 3.0f, 0.1f}, lambda), 0);
  EXPECT_EQ(counting.samples, 0);
  EXPECT_EQ(samplesFrom(oneSided, {0.2f, 0.0f, 0.1f}, lambda), 256);
  EXPECT_EQ(counting.samples, 256);
  // Two-sided: sampled, and lit, from behind as well.
  const AreaLight twoSided(counting, Spectrum::constant(2.0), /*twoSided=*/true);
  EXPECT_EQ(samplesFrom(twoSided, {0.2f, 3.0f, 0.1f}, lambda), 256);
  EXPECT_EQ(counting.samples, 512);
}

TEST(AreaLight, TwoSidedLampLightsBothSides) {
  const TriangleMesh mesh = lampFacingDown();
  const AreaLight light(mesh, Spectrum::constant(2.0), /*twoSided=*/true);
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.3f);
  EXPECT_EQ(samplesFrom(light, {0.2f, 0.0f, 0.1f}, lambda), 256);
  EXPECT_EQ(samplesFrom(light, {0.2f, 3.0f, 0.1f}, lambda), 256);
}

}  // namespace
}  // namespace camsim
