// captureSidecar (integrator/capture/capture_sidecar.h): camera.derived.aperture is the
// camera's own — a traced lens has its stop where the scene gives no camera.aperture (found
// by probing: "pinhole" for the double-Gauss at f/2).
#include "integrator/capture/capture_sidecar.h"

#include <gtest/gtest.h>

#include <string>

#include "integrator/scene/scene_loader.h"

namespace camsim {
namespace {

std::string derivedAperture(const std::string& camera) {
  CaptureResult r;
  r.description = loadSceneFromText(
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [16, 12]" + camera +
          "}\nshapes: [{type: sphere, centre: [0, 0, 3], radius: 1, emission: {luminance: 1}}]\n",
      "sidecar.yaml", CAMSIM_SOURCE_DIR);
  const std::string text = captureSidecar(r, true).str();
  const std::string key = "\"aperture\": \"";
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return "";
  return text.substr(at + key.size(), text.find('"', at + key.size()) - at - key.size());
}

TEST(CaptureSidecar, DerivedApertureIsTheCamerasOwn) {
  EXPECT_EQ(derivedAperture(""), "pinhole");
  EXPECT_EQ(derivedAperture(", aperture: {blades: 6}"), "6 blades");
  EXPECT_EQ(derivedAperture(", lens: {file: dgauss.50mm.dat}"), "circular");
  EXPECT_EQ(derivedAperture(", lens: {file: dgauss.50mm.dat}, aperture: {blades: 7}"), "7 blades");
}

}  // namespace
}  // namespace camsim
