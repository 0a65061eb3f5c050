// The scene loader's `lights:` list (integrator/scene/scene_loader_lights.cpp): unit
// conversions to the absolute quantities the lights use (cd, W, lm → W·sr⁻¹·nm⁻¹;
// lx, W/m² → W·m⁻²·nm⁻¹; environment scale or lux), directions from elevation/azimuth,
// the map rotation, and bad inputs rejected with file:line:column and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "integrator/lights/environment_light.h"
#include "integrator/lights/spot_light.h"
#include "integrator/scene/factory.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

using test::TempDir;

constexpr double kLightsLoaderDeg = M_PI / 180.0;

// Lines 1–4; the light is on line 5.
const std::string kLightPrefix =
    "camera: {position: [0, 1, 0], look_at: [0, 0, 0], up: [0, 0, 1]}\n"
    "materials: {m: {type: diffuse}}\n"
    "shapes: [{type: sphere, centre: [0, 0, 0], radius: 1, material: m}]\n"
    "lights:\n";

LightDescription loadLight(const std::string& light, const std::filesystem::path& dir = ".") {
  const SceneDescription scene =
      loadSceneFromText(kLightPrefix + "  - " + light + "\n", "test.yaml", dir);
  EXPECT_EQ(scene.lights.size(), 1u);
  return scene.lights.at(0);
}

// Loading fails at line 5, at the column of `token` in the light's line, naming `key`
// and saying `message`.
void expectError(const std::string& light, const std::string& token, const std::string& key,
                 const std::string& message, const std::filesystem::path& dir = ".") {
  const std::string line = "  - " + light;
  try {
    loadSceneFromText(kLightPrefix + line + "\n", "test.yaml", dir);
    ADD_FAILURE() << "no error for: " << light;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "test.yaml");
    EXPECT_EQ(e.where().line, 5) << e.what();
    EXPECT_EQ(e.where().column, static_cast<int>(line.find(token)) + 1) << e.what();
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

double relative(double value, double expected) {
  return value / expected - 1.0;
}

// 1 cd of D65: luminance(I) = 1 cd exactly (to float rounding) and I ∝ D65.
TEST(LightLoader, PointIntensityInCandela) {
  const LightDescription d = loadLight("{type: point, position: [1, 2, 3], intensity: 1}");
  EXPECT_EQ(d.kind, LightDescription::Kind::kPoint);
  EXPECT_NEAR(relative(luminance(d.spectrum), 1.0), 0.0, 1e-6);
  const Spectrum d65 = cieIlluminant("D65");
  EXPECT_NEAR(relative(d.spectrum(450.0f) / d.spectrum(600.0f), d65(450.0f) / d65(600.0f)), 0.0,
              1e-5);
  const LightDescription bb =
      loadLight("{type: point, position: [0, 2, 0], intensity: 250, spectrum: {blackbody: 2700}}");
  EXPECT_NEAR(relative(luminance(bb.spectrum), 250.0), 0.0, 1e-6);
}

// W: 4π ∫ I dλ = P; lm: 4π · luminance(I) = Φv; both equal the light's power().
TEST(LightLoader, PointPowerInWattsAndLumens) {
  const LightDescription w = loadLight("{type: point, position: [0, 2, 0], power: 2}");
  EXPECT_NEAR(relative(4.0 * M_PI * w.spectrum.sum(), 2.0), 0.0, 1e-6);
  EXPECT_NEAR(relative(makeLight(w)->power(), 2.0), 0.0, 1e-6);
  const LightDescription lm = loadLight("{type: point, position: [0, 2, 0], lumens: 800}");
  EXPECT_NEAR(relative(4.0 * M_PI * luminance(lm.spectrum), 800.0), 0.0, 1e-6);
}

// Spot: cd on the axis; lm and W over the cone, checked against a numerical ∫ falloff dω.
TEST(LightLoader, SpotIntensityLumensAndPower) {
  const LightDescription cd = loadLight(
      "{type: spot, position: [0, 2, 0], look_at: [0, 0, 0], cone_angle: 30, falloff_start: 25, "
      "intensity: 40}");
  EXPECT_NEAR(relative(luminance(cd.spectrum), 40.0), 0.0, 1e-6);
  EXPECT_NEAR(cd.coneAngle, 30.0 * kLightsLoaderDeg, 1e-6);
  EXPECT_NEAR(cd.falloffStart, 25.0 * kLightsLoaderDeg, 1e-6);
  EXPECT_NEAR(cd.direction.y, -1.0f, 1e-7f);
  const LightDescription lm = loadLight(
      "{type: spot, position: [0, 2, 0], direction: [0, -1, 0], cone_angle: 30, falloff_start: 10, "
      "lumens: 500}");
  const SpotLight spot(lm.position, lm.direction, lm.spectrum, lm.coneAngle, lm.falloffStart);
  double omega = 0.0;
  constexpr int kSteps = 20000;
  for (int k = 0; k < kSteps; ++k) {
    const double a = 0.5 * M_PI * (k + 0.5) / kSteps;
    const glm::vec3 w(static_cast<float>(std::sin(a)), -static_cast<float>(std::cos(a)), 0.0f);
    omega +=
        2.0 * M_PI * std::sin(a) * (0.5 * M_PI / kSteps) * static_cast<double>(spot.falloff(w));
  }
  EXPECT_NEAR(relative(omega * luminance(lm.spectrum), 500.0), 0.0, 1e-4);
  const LightDescription w =
      loadLight("{type: spot, position: [0, 2, 0], direction: [0, -1, 0], power: 3}");
  EXPECT_NEAR(w.coneAngle, 30.0 * kLightsLoaderDeg, 1e-6);  // defaults: 30°, falloff from 25°
  EXPECT_NEAR(w.falloffStart, 25.0 * kLightsLoaderDeg, 1e-6);
  EXPECT_NEAR(relative(makeLight(w)->power(), 3.0), 0.0, 1e-6);
}

// lx: luminance(E) = E_v; W/m²: ∫ E dλ; elevation/azimuth: toward the sun =
// (−cos el sin az, sin el, cos el cos az) (azimuth clockwise from +z, −x east).
TEST(LightLoader, DistantIlluminanceAndDirection) {
  const LightDescription d =
      loadLight("{type: distant, elevation: 30, azimuth: 90, illuminance: 100000}");
  EXPECT_EQ(d.kind, LightDescription::Kind::kDistant);
  EXPECT_NEAR(relative(luminance(d.spectrum), 1e5), 0.0, 1e-6);
  EXPECT_NEAR(d.direction.x, std::cos(30.0 * kLightsLoaderDeg), 1e-6);
  EXPECT_NEAR(d.direction.y, -0.5, 1e-6);
  EXPECT_NEAR(d.direction.z, 0.0, 1e-6);
  EXPECT_NEAR(d.angularDiameter, 0.53 * kLightsLoaderDeg, 1e-7);  // the sun by default
  const LightDescription n =
      loadLight("{type: distant, elevation: 45, illuminance: 1}");  // azimuth 0: north
  EXPECT_NEAR(n.direction.z, -std::sqrt(0.5), 1e-6);
  const LightDescription w = loadLight(
      "{type: distant, direction: [0, -2, 0], irradiance: 100, angular_diameter: 0, spectrum: 1}");
  EXPECT_NEAR(relative(w.spectrum.sum(), 100.0), 0.0, 1e-6);
  EXPECT_EQ(w.angularDiameter, 0.0f);
  EXPECT_EQ(w.direction, glm::vec3(0.0f, -1.0f, 0.0f));
}

Image rgbMap(int w, int h, float value) {
  Image img(w, h, {"R", "G", "B"});
  for (float& p : img.pixels) p = value;
  return img;
}

// scale is the multiplier; illuminance: E_v of the map at scale 1 times the scale is the
// requested lux; rotation turns the map clockwise seen from above (towards the east).
TEST(LightLoader, EnvironmentScaleIlluminanceAndRotation) {
  TempDir dir;
  Image sky = rgbMap(8, 4, 0.5f);
  sky.at(2, 0, 0) = 30.0f;
  writeExr(dir.path() / "sky.exr", sky, {}, std::nullopt);
  const LightDescription s =
      loadLight("{type: environment, file: sky.exr, scale: 2.5}", dir.path());
  EXPECT_EQ(s.kind, LightDescription::Kind::kEnvironment);
  EXPECT_FLOAT_EQ(s.spectrum(550.0f), 2.5f);
  ASSERT_TRUE(s.image);
  EXPECT_EQ(s.image->width, 8);
  const LightDescription lx =
      loadLight("{type: environment, file: sky.exr, illuminance: 5000}", dir.path());
  EXPECT_NEAR(relative(EnvironmentLight::zenithIlluminance(*lx.image) *
                           static_cast<double>(lx.spectrum(550.0f)),
                       5000.0),
              0.0, 1e-6);
  // The map centre (u = ½; map direction −x) lies north (+z), and east (−x) after 90°.
  const glm::dvec3 centre(EnvironmentLight::directionOf({0.5f, 0.5f}));
  const glm::dvec3 north = s.worldFromLight * centre;
  EXPECT_NEAR(north.z, 1.0, 1e-6);
  const LightDescription r =
      loadLight("{type: environment, file: sky.exr, scale: 1, rotation: 90}", dir.path());
  EXPECT_NEAR((r.worldFromLight * centre).x, -1.0, 1e-6);
  EXPECT_NEAR((r.worldFromLight * glm::dvec3(0.0, 0.0, 1.0)).y, 1.0, 1e-9);  // zenith up
}

TEST(LightLoader, BadValuesAreRejectedWithTheirLocation) {
  expectError("{type: laser}", "laser", "lights[0].type", "unknown light type");
  expectError("{type: point, position: [0, 0, 0], intensity: 1, colour: 2}", "colour",
              "lights[0].colour", "unknown key");
  expectError("{type: point, position: [0, 0, 0], intensity: -5}", "-5", "lights[0].intensity",
              "out of range");
  expectError("{type: point, position: [0, 0, 0], intensity: 1, power: 7}", "7", "lights[0].power",
              "give only one of");
  expectError("{type: point, position: [0, 0, 0]}", "{type", "lights[0]", "needs one of");
  expectError("{type: point, position: [0, 0, 0], intensity: 5, spectrum: 0}", "0}",
              "lights[0].spectrum", "no visible power");
  expectError("{type: point, intensity: 1}", "{type", "lights[0].position",
              "required key is missing");
  expectError("{type: spot, position: [0, 0, 0], direction: [0, 0, 0], intensity: 1}",
              "[0, 0, 0], int", "lights[0].direction", "must not be zero");
  expectError(
      "{type: spot, position: [0, 0, 0], direction: [0, -1, 0], cone_angle: 20, falloff_start: 25, "
      "intensity: 1}",
      "25", "lights[0].falloff_start", "must not exceed cone_angle");
  expectError("{type: distant, elevation: 95, illuminance: 1}", "95", "lights[0].elevation",
              "out of range");
  expectError("{type: distant, direction: [0, -1, 0], elevation: 10, illuminance: 1}", "[0, -1, 0]",
              "lights[0].direction", "not both");
  expectError("{type: distant, direction: [0, -1, 0], illuminance: 1, angular_diameter: 100}",
              "100", "lights[0].angular_diameter", "out of range");
  expectError("{type: point, position: [0, 0, 0], intensity: 1e300}", "1e300",
              "lights[0].intensity", "out of range");
}

TEST(LightLoader, BadEnvironmentMapsAreRejectedWithTheirLocation) {
  TempDir dir;
  expectError("{type: environment, file: nothere.exr, scale: 1}", "nothere", "lights[0].file",
              "not found", dir.path());
  std::ofstream(dir.path() / "text.exr") << "not an exr\n";
  expectError("{type: environment, file: text.exr, scale: 1}", "text.exr", "lights[0].file",
              "cannot read EXR", dir.path());
  Image grey(4, 2, {"Y"});
  writeExr(dir.path() / "grey.exr", grey, {}, std::nullopt);
  expectError("{type: environment, file: grey.exr, scale: 1}", "grey.exr", "lights[0].file",
              "channels R, G and B", dir.path());
  writeExr(dir.path() / "black.exr", rgbMap(4, 2, 0.0f), {}, std::nullopt);
  expectError("{type: environment, file: black.exr, scale: 1}", "black.exr", "lights[0].file",
              "is black", dir.path());
  Image nan = rgbMap(4, 2, 1.0f);
  nan.at(1, 1, 2) = std::nanf("");
  writeExr(dir.path() / "nan.exr", nan, {}, std::nullopt);
  expectError("{type: environment, file: nan.exr, scale: 1}", "nan.exr", "lights[0].file",
              "non-finite", dir.path());
  writeExr(dir.path() / "ok.exr", rgbMap(4, 2, 1.0f), {}, std::nullopt);
  expectError("{type: environment, file: ok.exr, scale: 1, illuminance: 3}", "3}",
              "lights[0].illuminance", "give only one of", dir.path());
  expectError("{type: environment, file: ok.exr}", "{type", "lights[0]", "needs one of",
              dir.path());
  expectError("{type: environment, file: ok.exr, scale: 1, position: [0, 0, 0]}", "position",
              "lights[0].position", "unknown key", dir.path());
}

}  // namespace
}  // namespace camsim
