// Point, spot and distant lights against closed forms, rendered through the scene loader,
// Scene and render() (luminance Y in cd/m², see light_test_support.h):
//  - a Lambertian floor of reflectance ρ under a point light of intensity I (cd) at
//    distance d and angle θ from the normal has luminance ρ/π · I cos θ / d²;
//  - a spot on its axis equals the point light, beyond its cone it gives 0, its falloff
//    is monotone and its power is the integral of its intensity;
//  - under a sun of illuminance E (lx) at zenith angle z the floor has ρ/π · E cos z, for
//    a delta sun and for the 0.53° disc alike; the disc itself has luminance E/(π sin²α);
//  - extreme lights (1e9 cd, a sphere of radius 0.1 mm) stay finite and exact.
// Unless said otherwise the noise is far below the tolerance: delta lights are sampled
// exactly and only the wavelengths and the position in the pixel vary.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "integrator/lights/distant_light.h"
#include "integrator/lights/point_light.h"
#include "integrator/lights/spot_light.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"
#include "tests/integrator/render_test_support.h"

namespace camsim {
namespace {

using test::cameraAboveOrigin;
using test::floorOf;
using test::renderLuminance;

constexpr double kLightsDeg = M_PI / 180.0;

std::string vec(double x, double y, double z) {
  return "[" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + "]";
}

// Position of a light at distance d and angle θ from the floor's normal above the origin.
std::string lightPosition(double d, double thetaDeg) {
  return vec(d * std::sin(thetaDeg * kLightsDeg), d * std::cos(thetaDeg * kLightsDeg), 0.0);
}

// cos θ / d² at the floor point (x, 0, z) from a light at distance d and angle θ from the
// normal above the origin; averaged over the pixel's footprint it is the pixel's
// expectation (within < 1 % of its value at the origin for the 2 × 2 images).
double cosOverD2(double d, double thetaDeg, double x, double z) {
  const glm::dvec3 v =
      glm::dvec3(d * std::sin(thetaDeg * kLightsDeg), d * std::cos(thetaDeg * kLightsDeg), 0.0) -
      glm::dvec3(x, 0.0, z);
  const double len = glm::length(v);
  return v.y / (len * len * len);
}

double pixelCosOverD2(int n, int px, int py, double d, double thetaDeg) {
  return test::footprintMean(n, px, py,
                             [&](double x, double z) { return cosOverD2(d, thetaDeg, x, z); });
}

// One pixel centred on the origin; measured relative error 4e-5 (wavelength noise);
// tolerance 1 %.
TEST(PointLight, LambertianFloorReadsRhoOverPiTimesICosOverD2) {
  test::MaxError err;
  for (const double thetaDeg : {0.0, 40.0, 70.0}) {
    const double rho = 0.5, candela = 100.0, d = 1.5;
    const std::string yaml = cameraAboveOrigin(1) + floorOf(rho) +
                             "lights:\n  - {type: point, position: " + lightPosition(d, thetaDeg) +
                             ", intensity: 100}\n";
    const test::LuminanceImage img = renderLuminance(yaml, 256);
    const double expected = rho / M_PI * candela * pixelCosOverD2(1, 0, 0, d, thetaDeg);
    EXPECT_NEAR(pixelCosOverD2(1, 0, 0, d, thetaDeg) / (std::cos(thetaDeg * kLightsDeg) / (d * d)),
                1.0, 1e-3);
    EXPECT_LT(err(img.at(0, 0), expected), 0.01) << "theta " << thetaDeg << ": " << img.at(0, 0);
    EXPECT_EQ(img.stats.rejectedSamples, 0u);
  }
}

// A spot at distance 1.5 m and 40° from the normal above the origin, its axis in the
// plane of incidence at angle β from the normal (β = 40°: aimed at the origin).
std::string spotScene(double betaDeg, double coneDeg, double falloffDeg) {
  return cameraAboveOrigin(1) + floorOf(0.5) +
         "lights:\n  - {type: spot, position: " + lightPosition(1.5, 40.0) + ", direction: " +
         vec(-std::sin(betaDeg * kLightsDeg), -std::cos(betaDeg * kLightsDeg), 0.0) +
         ", cone_angle: " + std::to_string(coneDeg) +
         ", falloff_start: " + std::to_string(falloffDeg) + ", intensity: 100}\n";
}

// Same seed, same paths: on its axis the spot reads what the point light reads (measured
// ratio 1 to 1e-7; tolerance 1e-4); beyond its cone the floor is exactly black.
TEST(SpotLight, OnAxisEqualsPointLightAndBeyondTheConeIsBlack) {
  test::MaxError err;
  const std::string point = cameraAboveOrigin(1) + floorOf(0.5) +
                            "lights:\n  - {type: point, position: " + lightPosition(1.5, 40.0) +
                            ", intensity: 100}\n";
  const double reference = renderLuminance(point, 64).at(0, 0);
  EXPECT_LT(err(renderLuminance(spotScene(40.0, 20.0, 15.0), 64).at(0, 0), reference), 1e-4);
  // Axis 30° away from the origin with a 20° cone: the origin is outside, either side.
  EXPECT_EQ(renderLuminance(spotScene(10.0, 20.0, 15.0), 16).at(0, 0), 0.0);
  EXPECT_EQ(renderLuminance(spotScene(70.0, 20.0, 15.0), 16).at(0, 0), 0.0);
  // In the falloff (axis 17.5° away: half way between 15° and 20°) the floor is lit, less.
  const double inFalloff = renderLuminance(spotScene(40.0 - 17.5, 20.0, 15.0), 16).at(0, 0);
  EXPECT_GT(inFalloff, 0.0);
  EXPECT_LT(inFalloff, 0.9 * reference);
}

// The falloff is 1 inside falloff_start, 0 beyond cone_angle and never increases with the
// angle in between; the intensity returned by sample() follows it.
TEST(SpotLight, FalloffIsMonotoneAndPowerIsTheIntegralOfTheIntensity) {
  test::MaxError err;
  const Spectrum intensity = Spectrum::constant(2.0);
  const SpotLight spot({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, intensity,
                       static_cast<float>(30.0 * kLightsDeg),
                       static_cast<float>(20.0 * kLightsDeg));
  float previous = 1.0f;
  for (int k = 0; k <= 400; ++k) {
    const double a = 40.0 * kLightsDeg * k / 400.0;
    const glm::vec3 w(static_cast<float>(std::sin(a)), 0.0f, static_cast<float>(std::cos(a)));
    const float f = spot.falloff(w);
    EXPECT_LE(f, previous) << "angle " << a / kLightsDeg;
    if (a < 19.9 * kLightsDeg) {
      EXPECT_EQ(f, 1.0f);
    }
    if (a > 30.1 * kLightsDeg) {
      EXPECT_EQ(f, 0.0f);
    }
    previous = f;
  }
  // Φ = ∫ I dω ∫ dλ by the midpoint rule in θ (falloff ∝ smoothstep in cos θ): agrees with
  // power() to 1e-5 (measured 1e-7).
  double integral = 0.0;
  constexpr int kSteps = 20000;
  for (int k = 0; k < kSteps; ++k) {
    const double a = M_PI * (k + 0.5) / kSteps;
    const glm::vec3 w(static_cast<float>(std::sin(a)), 0.0f, static_cast<float>(std::cos(a)));
    integral += 2.0 * M_PI * std::sin(a) * (M_PI / kSteps) * static_cast<double>(spot.falloff(w));
  }
  EXPECT_LT(err(integral * intensity.sum(), spot.power()), 1e-5);
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.3f);
  const auto inside = spot.sample({0.0f, 0.0f, 2.0f}, 0.0f, 0.5f, {0.5f, 0.5f}, lambda);
  ASSERT_TRUE(inside);
  EXPECT_TRUE(inside->delta);
  EXPECT_FLOAT_EQ(inside->L[0], 2.0f / 4.0f);
  EXPECT_FALSE(spot.sample({0.0f, 0.0f, -2.0f}, 0.0f, 0.5f, {0.5f, 0.5f}, lambda));
}

std::string sunScene(double zenithDeg, double diameterDeg) {
  return cameraAboveOrigin(2) + floorOf(0.5) +
         "lights:\n  - {type: distant, elevation: " + std::to_string(90.0 - zenithDeg) +
         ", azimuth: 30, illuminance: 1000, angular_diameter: " + std::to_string(diameterDeg) +
         "}\n";
}

// ρ/π · E cos z for the delta sun and the 0.53° disc, and the two agree: measured ≤ 4.3e-4
// over all three checks; tolerance 1 %.
TEST(DistantLight, FloorUnderTheSunReadsRhoOverPiTimesECosZenith) {
  test::MaxError err;
  for (const double zenith : {0.0, 30.0, 60.0}) {
    const double expected = 0.5 / M_PI * 1000.0 * std::cos(zenith * kLightsDeg);
    const test::LuminanceImage delta = renderLuminance(sunScene(zenith, 0.0), 64);
    const test::LuminanceImage disc = renderLuminance(sunScene(zenith, 0.53), 256);
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) {
        EXPECT_LT(err(delta.at(x, y), expected), 0.01) << zenith << " delta " << delta.at(x, y);
        EXPECT_LT(err(disc.at(x, y), expected), 0.01) << zenith << " disc " << disc.at(x, y);
        EXPECT_LT(err(disc.at(x, y), delta.at(x, y)), 0.01) << zenith;
      }
  }
}

// A camera looking at the centre of the 0.53° sun with a 4 mrad field of view (inside the
// disc of radius 4.6 mrad) sees L = E/(π sin²α): luminance 1000 lx / (π sin²α).
// Measured relative error 5.6e-4 (wavelength noise only); tolerance 1 %.
TEST(DistantLight, TheSunDiscHasRadianceEOverPiSin2Alpha) {
  test::MaxError err;
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 1, 1], up: [0, 1, 0], sensor_width_mm: 0.2,\n"
      "         sensor_height_mm: 0.2, focal_length_mm: 50, resolution: [4, 4]}\n"
      "materials: {m: {type: diffuse}}\n"
      "shapes: [{type: sphere, centre: [0, -5, -5], radius: 0.1, material: m}]\n"
      "lights:\n  - {type: distant, direction: [0, -1, -1], illuminance: 1000, angular_diameter: "
      "0.53}\n";
  const test::LuminanceImage img = renderLuminance(yaml, 64);
  const double alpha = 0.5 * 0.53 * kLightsDeg;
  const double expected = 1000.0 / (M_PI * std::sin(alpha) * std::sin(alpha));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_LT(err(img.at(x, y), expected), 0.01) << img.at(x, y);
  EXPECT_EQ(img.stats.rejectedSamples, 0u);
}

// Sampling the disc: every sample lies in the cone, Le and pdfDirection agree with it, and
// the estimate of the irradiance on a plane facing the sun is E (exact per sample up to
// cos θ ≥ cos α: measured 2e-8; tolerance 1e-4).
TEST(DistantLight, DiscSamplesAgreeWithLeAndPdfDirection) {
  test::MaxError err;
  const DistantLight sun(Spectrum::constant(3.0), {0.0f, -1.0f, 0.0f},
                         static_cast<float>(0.53 * kLightsDeg));
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.4f);
  double e = 0.0;
  constexpr int kN = 4096;
  for (int k = 0; k < kN; ++k) {
    const glm::vec2 u((static_cast<float>(k % 64) + 0.5f) / 64.0f,
                      (static_cast<float>(k / 64) + 0.5f) / 64.0f);
    const auto ls = sun.sample({0.0f, 0.0f, 0.0f}, 0.0f, 0.5f, u, lambda);
    ASSERT_TRUE(ls);
    EXPECT_TRUE(ls->infinite);
    EXPECT_FALSE(ls->delta);
    EXPECT_EQ(sun.Le(ls->wi, lambda)[0], ls->L[0]);
    EXPECT_EQ(sun.pdfDirection(ls->wi), ls->pdf);
    e += static_cast<double>(ls->L[0]) * static_cast<double>(ls->wi.y) /
         static_cast<double>(ls->pdf);
  }
  EXPECT_LT(err(e / kN, 3.0), 1e-4);
  EXPECT_EQ(sun.pdfDirection({0.0f, 1.0f, 0.01f}), 0.0f);
  EXPECT_TRUE(sun.Le({0.0f, 1.0f, 0.01f}, lambda).isZero());
}

// 1e9 cd at 2 m, 30° off the normal: finite, ρ/π · I cos θ / d² (measured 4.4e-4), no
// rejected samples; tolerance 1 %.
TEST(ExtremeLights, BillionCandelaPointLight) {
  test::MaxError err;
  const std::string yaml = cameraAboveOrigin(2) + floorOf(0.5) +
                           "lights:\n  - {type: point, position: " + lightPosition(2.0, 30.0) +
                           ", intensity: 1e9}\n";
  const test::LuminanceImage img = renderLuminance(yaml, 64);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const double expected = 0.5 / M_PI * 1e9 * pixelCosOverD2(2, x, y, 2.0, 30.0);
      EXPECT_TRUE(std::isfinite(img.at(x, y)));
      EXPECT_LT(err(img.at(x, y), expected), 0.01) << img.at(x, y);
    }
  EXPECT_EQ(img.stats.rejectedSamples, 0u);
}

// A sphere of radius 0.1 mm and luminance 1e12 cd/m² 1 m away, 30° off the normal: its
// intensity is L π r², so the floor reads ρ/π · L π r² cos θ / d² (exact for a sphere
// above the horizon). Measured 8e-5; tolerance 1 %.
TEST(ExtremeLights, TinySphereEmitter) {
  test::MaxError err;
  const std::string yaml = cameraAboveOrigin(2) + floorOf(0.5) +
                           "  - {type: sphere, centre: " + lightPosition(1.0, 30.0) +
                           ", radius: 1e-4, emission: {luminance: 1e12}}\n";
  const test::LuminanceImage img = renderLuminance(yaml, 256);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const double expected = 0.5 / M_PI * 1e12 * M_PI * 1e-8 * pixelCosOverD2(2, x, y, 1.0, 30.0);
      EXPECT_TRUE(std::isfinite(img.at(x, y)));
      EXPECT_LT(err(img.at(x, y), expected), 0.01) << img.at(x, y);
    }
  EXPECT_EQ(img.stats.rejectedSamples, 0u);
}

// The point light's sample(): E⊥ = I/d² along the unit direction to the light, delta.
TEST(PointLight, SampleIsIntensityOverDistanceSquared) {
  test::MaxError err;
  const PointLight light({1.0f, 2.0f, 2.0f}, Spectrum::constant(9.0));
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.1f);
  const auto ls = light.sample({0.0f, 0.0f, 0.0f}, 0.25f, 0.5f, {0.5f, 0.5f}, lambda);
  ASSERT_TRUE(ls);
  EXPECT_TRUE(ls->delta);
  EXPECT_FALSE(ls->infinite);
  EXPECT_FLOAT_EQ(ls->L[0], 1.0f);
  EXPECT_FLOAT_EQ(ls->wi.x, 1.0f / 3.0f);
  EXPECT_EQ(ls->point.p, glm::vec3(1.0f, 2.0f, 2.0f));
  EXPECT_LT(err(light.power(), 4.0 * M_PI * 9.0 * kSpectrumSamples), 1e-9);
}

}  // namespace
}  // namespace camsim
