// Tests for integrator/scene/scene_loader_sensor.cpp: the `sensor:` block's model is a preset or
// a sensor file relative to the scene (docs/scene-format.md), never to the current folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

std::string sceneWithSensor(const std::string& model) {
  return "camera: {position: [0, 0, -1], look_at: [0, 0, 0]}\n"
         "sensor: {model: " +
         model +
         "}\n"  // line 2
         "shapes: [{type: sphere, centre: [0, 0, 0], radius: 1, emission: {luminance: 1}}]\n";
}

TEST(SceneLoaderSensor, APresetLoadsAtItsBaseIso) {
  const SceneDescription d = loadSceneFromText(sceneWithSensor("fullframe-d850"), "s.yaml", ".");
  ASSERT_TRUE(d.sensor.has_value());
  EXPECT_EQ(d.sensor->spec.name, "fullframe-d850");
  EXPECT_EQ(d.sensor->iso, 64.0);
}

TEST(SceneLoaderSensor, NoiseModesByName) {
  const auto load = [](const std::string& noise) {
    return loadSceneFromText(sceneWithSensor("ideal-xyz, noise: " + noise), "s.yaml", ".");
  };
  EXPECT_EQ(load("photon").sensor->noise, NoiseMode::kPhoton);
  EXPECT_EQ(load("none").sensor->noise, NoiseMode::kNone);
  try {
    load("loud");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "sensor.noise") << e.what();
    EXPECT_NE(e.message().find("unknown noise mode 'loud' (known: none, photon, full)"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneLoaderSensor, ASensorFileIsRelativeToTheScene) {
  test::TempDir dir;
  const fs::path scenes = dir.path() / "scenes";
  test::writeFile(scenes / "qe.csv", "wavelength_nm,mono\n400,0.2\n700,0.4\n");
  test::writeFile(scenes / "cam.yaml",
                  "pixel_pitch_um: 2\ncfa: mono\nqe: {csv: qe.csv, columns: [mono]}\n");
  const SceneDescription d =
      loadSceneFromText(sceneWithSensor("cam.yaml"), (scenes / "s.yaml").string(), scenes);
  ASSERT_TRUE(d.sensor.has_value());
  EXPECT_EQ(d.sensor->spec.name, "cam");
  EXPECT_DOUBLE_EQ(d.sensor->spec.pixelPitchM, 2e-6);
  ASSERT_EQ(d.inputFiles.size(), 2u);
  EXPECT_TRUE(fs::equivalent(d.inputFiles[0], scenes / "cam.yaml"));
  EXPECT_TRUE(fs::equivalent(d.inputFiles[1], scenes / "qe.csv"));

  // A path that is no file there (here a folder of that name) is an error at the model
  // key naming the place beside the scene; camsim does not fall back to the current
  // folder (where it once looked, naming "x.yaml" alone).
  fs::create_directories(scenes / "x.yaml");
  try {
    loadSceneFromText(sceneWithSensor("x.yaml"), "s.yaml", scenes);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "sensor.model") << e.what();
    EXPECT_EQ(e.where().line, 2) << e.what();
    EXPECT_NE(e.message().find((scenes / "x.yaml").string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace camsim
