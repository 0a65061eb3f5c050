// writeDatasetMetadata (integrator/capture/dataset_writer.h): the camera poses of
// cameras.json and transforms.json keep the position the scene gave, however far from the
// origin (found by probing: written with 10 significant digits, a camera at 1.2e8 m was
// 2.3 cm off, 7.8 px for a point 3 m ahead at fx = 1000; scenes allow coordinates to 1e15 m).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "integrator/capture/dataset_writer.h"
#include "integrator/scene/scene_loader.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

// The 16 numbers of the first matrix after `key` in `json`.
std::vector<double> matrixAfter(const std::string& json, const std::string& key) {
  std::vector<double> out;
  std::size_t at = json.find("\"" + key + "\"");
  if (at == std::string::npos) return out;
  at = json.find('[', at);
  const char* p = json.c_str() + at;
  while (out.size() < 16 && *p) {
    if (*p == '-' || (*p >= '0' && *p <= '9')) {
      char* end = nullptr;
      out.push_back(std::strtod(p, &end));
      p = end;
    } else {
      ++p;
    }
  }
  return out;
}

TEST(DatasetWriterPose, FarCameraPositionsAreWrittenExactly) {
  const glm::dvec3 position(123456789.123456, 20.5, 76543210.987654);
  const SceneDescription d = loadSceneFromText(
      "camera: {position: [123456789.123456, 20.5, 76543210.987654], look_at: [123456789.123456, "
      "20.5, 76543213.987654], resolution: [32, 24]}\n"
      "shapes: [{type: sphere, centre: [123456789.123456, 20.5, 76543215], radius: 1, "
      "emission: {luminance: 1}}]\n",
      "far.yaml", ".");
  DatasetFrame frame;
  frame.image = "far_0000.png";
  frame.camera = d.camera;
  frame.renderOrigin = d.renderOrigin;
  const test::TempDir dir;
  (void)writeDatasetMetadata({frame}, dir.path());
  for (const auto& [file, key] : {std::pair{"cameras.json", "world_from_camera_opencv"},
                                  std::pair{"cameras.json", "world_from_camera_opengl"},
                                  std::pair{"transforms.json", "transform_matrix"}}) {
    const std::vector<double> m = matrixAfter(test::readFile(dir.path() / file), key);
    ASSERT_EQ(m.size(), 16U) << file << " " << key;
    // Rows: the translation is each row's fourth number.
    EXPECT_NEAR(m[3], position.x, 1e-6) << file << " " << key;
    EXPECT_NEAR(m[7], position.y, 1e-6) << file << " " << key;
    EXPECT_NEAR(m[11], position.z, 1e-6) << file << " " << key;
  }
}

}  // namespace
}  // namespace camsim
