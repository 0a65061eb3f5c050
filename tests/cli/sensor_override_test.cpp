// The sensor overrides' errors (integrator/scene/overrides.cpp), found by probing: an empty
// sensor file given as --sensor was "<command line>: key 'sensor.model': expected a mapping"
// with no file named; an --iso outside a calibrated sensor's iso_table was "<input>: key
// 'iso'", found when the sensor model was built. Now the option's key names both, and the
// file when the error has one.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "integrator/scene/overrides.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

const char* kScene =
    "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [8, 8]}\n"
    "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
    "shapes: [{type: sphere, centre: [0, 0, 0], radius: 1, material: grey}]\n";

InputError overrideError(const Overrides& o) {
  SceneDescription d = loadSceneFromText(kScene, "base.yaml", ".");
  try {
    applyOverrides(d, o, {"<command line>", 0, 0});
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "applied";
  return InputError({}, "", "");
}

TEST(SensorOverride, AnEmptySensorFileIsNamed) {
  test::TempDir dir;
  const fs::path empty = dir.path() / "empty_sensor.yaml";
  test::writeFile(empty, "");
  Overrides o;
  o.sensor = empty.string();
  const InputError e = overrideError(o);
  EXPECT_EQ(e.where().file, "<command line>");
  EXPECT_EQ(e.key(), "sensor.model");
  EXPECT_NE(e.message().find(empty.string() + ": "), std::string::npos) << e.what();
}

TEST(SensorOverride, AnIsoOutsideTheCalibrationNamesTheOptionsKey) {
  Overrides o;
  o.sensor = "eld-canon-5d4";
  o.iso = 50.0;
  const InputError e = overrideError(o);
  EXPECT_EQ(e.where().file, "<command line>");
  EXPECT_EQ(e.key(), "sensor.iso");
  EXPECT_NE(e.message().find("ISO 50 is outside the range"), std::string::npos) << e.what();
  // Inside it, the override applies.
  o.iso = 400.0;
  SceneDescription d = loadSceneFromText(kScene, "base.yaml", ".");
  applyOverrides(d, o, {"<command line>", 0, 0});
  ASSERT_TRUE(d.sensor.has_value());
  EXPECT_EQ(d.sensor->iso, 400.0);
}

// The camera's own sensor size is replaced by resolution × pixel pitch (as documented), and
// said so with the new size (found by probing: a 36 mm sensor_width_mm became 11.2 µm
// without a word); a scene without them gets no note.
TEST(SensorOverride, ReplacingTheCamerasSensorSizeIsNoted) {
  SceneDescription d = loadSceneFromText(
      "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [8, 8], sensor_width_mm: "
      "36, sensor_height_mm: 24}\n"
      "shapes: [{type: sphere, centre: [0, 0, 0], radius: 1, emission: {luminance: 1}}]\n",
      "wide.yaml", ".");
  Overrides o;
  o.sensor = "smartphone-1.4um";
  applyOverrides(d, o, {"<command line>", 0, 0});
  EXPECT_DOUBLE_EQ(d.camera.sensorSize.x, 8 * 1.4e-6);
  ASSERT_EQ(d.notes.size(), 1u);
  EXPECT_NE(d.notes[0].find("replaces the scene's camera.sensor_width_mm (wide.yaml:1), "
                            "camera.sensor_height_mm (wide.yaml:1): its sensor is 0.0112 × "
                            "0.0112 mm"),
            std::string::npos)
      << d.notes[0];
  SceneDescription plain = loadSceneFromText(kScene, "base.yaml", ".");
  applyOverrides(plain, o, {"<command line>", 0, 0});
  EXPECT_TRUE(plain.notes.empty());
}

}  // namespace
}  // namespace camsim
