// Scenes that must render exactly as a closed form or a twin scene says:
//  - lights that are all dark (luminance 0, scale 0, an all-zero CSV spectrum, emission
//    {rgb: [0, 0, 0]}) give an image that is 0 everywhere, with no rejected sample — they
//    used to abort in DiscreteDistribution::sample (no light has power to be picked);
//  - a scene moved 10⁶ m from the world origin renders the same bytes as at the origin:
//    render space is the camera's rest position, and every world-space input (sphere
//    centre, rectangle, inline mesh, mesh file with translate, mesh file with world
//    coordinates, point and spot light, keyframes of a moving shape, a moving camera) is
//    shifted in double before it is stored in float. The offsets are integers and the
//    scene's coordinates have short binary fractions, so both shifts are exact and any
//    rounding of a world coordinate to float (6 cm at 10⁶ m) shows as a changed pixel.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "tests/integrator/render_test_support.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::num;

using test::LuminanceImage;
using test::renderLuminance;

// A floor under one emitter of the given emission, seen from 1 m.
std::string darkRoom(const std::string& emission) {
  return "camera: {position: [0, 1, -1], look_at: [0, 0, 0], sensor_width_mm: 36,\n"
         "         sensor_height_mm: 24, focal_length_mm: 24, resolution: [12, 8]}\n"
         "materials: {floor: {type: diffuse, reflectance: 0.8}}\n"
         "shapes:\n"
         "  - {type: rectangle, corner: [-2, 0, -2], edge_u: [4, 0, 0], edge_v: [0, 0, 4],\n"
         "     material: floor}\n"
         "  - {type: sphere, centre: [0, 0.5, 0], radius: 0.2, material: floor,\n"
         "     emission: " +
         emission + "}\n";
}

TEST(DarkLights, RenderBlackWithoutAborting) {
  test::TempDir dir;
  test::writeFile(dir.path() / "zero.csv", "wavelength_nm,power\n360,0\n830,0\n");
  for (const std::string emission :
       {"{luminance: 0}", "{scale: 0}", "{scale: 1, spectrum: {csv: zero.csv}}",
        "{scale: 1, spectrum: {rgb: [0, 0, 0]}}", "{luminance: 0, two_sided: true}"}) {
    const LuminanceImage img = renderLuminance(darkRoom(emission), 8, 1, dir.path());
    EXPECT_EQ(img.stats.rejectedSamples, 0u) << emission;
    for (int y = 0; y < img.y.height; ++y)
      for (int x = 0; x < img.y.width; ++x)
        ASSERT_EQ(img.at(x, y), 0.0) << emission << " pixel " << x << "," << y;
  }
  // One dark light beside a lit one: the dark one is never picked, the image is lit.
  const std::string twoLights =
      darkRoom("{luminance: 0}") +
      "  - {type: sphere, centre: [0.5, 0.5, 0], radius: 0.1, emission: {luminance: 1000}}\n";
  const LuminanceImage lit = renderLuminance(twoLights, 8);
  EXPECT_EQ(lit.stats.rejectedSamples, 0u);
  EXPECT_GT(lit.at(6, 4), 0.0);
}

// Everything that takes a world position, offset by o. The camera moves (translate keys
// are offsets from its rest position) and so does the ball (keys are world positions).
std::string farScene(glm::dvec3 o, const std::string& meshDir) {
  auto p = [&](double x, double y, double z) {
    return "[" + num(o.x + x) + ", " + num(o.y + y) + ", " + num(o.z + z) + "]";
  };
  return "camera: {position: " + p(0, 1.5, -4) + ", look_at: " + p(0, 0.5, 0) +
         ", sensor_width_mm: 36, sensor_height_mm: 24,\n"
         "         focal_length_mm: 35, f_number: 4, focus_distance_m: 4, aperture: {blades: 6},\n"
         "         resolution: [48, 32], shutter: {open: 0, close: 0.02},\n"
         "         motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.02, translate: [0.25, 0, "
         "0]}]}\n"
         "render: {max_depth: 3}\n"
         "materials: {grey: {type: diffuse, reflectance: 0.5}, red: {type: diffuse, "
         "reflectance: {rgb: [0.8, 0.2, 0.1]}}}\n"
         "shapes:\n"
         "  - {type: rectangle, corner: " +
         p(-3, 0, -3) +
         ", edge_u: [6, 0, 0], edge_v: [0, 0, 6], material: grey}\n"
         "  - {type: sphere, centre: " +
         p(-1, 0.5, 0.5) +
         ", radius: 0.5, material: red}\n"
         "  - {type: sphere, centre: [0, 0, 0], radius: 0.375, material: grey,\n"
         "     motion: [{time: 0, translate: " +
         p(0.5, 0.375, -1) + "}, {time: 0.02, translate: " + p(1, 0.375, -1) +
         ", rotate: {axis: [0, 1, 0], angle_deg: 30}}]}\n"
         "  - {type: mesh, material: red, vertices: [" +
         p(1, 0, 1) + ", " + p(2, 0, 1) + ", " + p(1.5, 1, 1) +
         "], faces: [[0, 1, 2]]}\n"
         "  - {type: mesh, file: " +
         meshDir + "/local.obj, translate: " + p(-0.5, 0, 1.5) +
         ", material: grey}\n"
         "  - {type: mesh, file: " +
         meshDir + "/world" + (o.x == 0.0 ? "0" : "1") +
         ".obj, material: red}\n"
         "  - {type: rectangle, corner: " +
         p(-0.5, 2.5, -0.5) +
         ", edge_u: [1, 0, 0], edge_v: [0, 0, 1], emission: {luminance: 2000}}\n"
         "lights:\n"
         "  - {type: point, position: " +
         p(-2, 2, -2) +
         ", intensity: 50}\n"
         "  - {type: spot, position: " +
         p(2, 3, -1) + ", look_at: " + p(1.5, 0, 1) + ", cone_angle: 30, intensity: 200}\n";
}

std::string worldObj(glm::dvec3 o) {
  std::string s;
  for (const auto& v : {glm::dvec3(-2, 0, 2), glm::dvec3(-1.5, 0, 2), glm::dvec3(-1.75, 0.75, 2)})
    s += "v " + num(o.x + v.x) + " " + num(o.y + v.y) + " " + num(o.z + v.z) + "\n";
  return s + "f 1 2 3\n";
}

TEST(FarFromOrigin, EveryWorldSpaceInputRendersTheSameBytes) {
  test::TempDir dir;
  const glm::dvec3 far(1e6, -2e6, 3e6);
  test::writeFile(dir.path() / "local.obj",
                  "v 0 0 0\nv 0.5 0 0\nv 0.25 0.5 0\nv 0.25 0.25 -0.25\nf 1 2 3\nf 1 3 4\n");
  test::writeFile(dir.path() / "world0.obj", worldObj(glm::dvec3(0.0)));
  test::writeFile(dir.path() / "world1.obj", worldObj(far));
  const std::string meshDir = dir.path().string();
  const LuminanceImage near = renderLuminance(farScene(glm::dvec3(0.0), meshDir), 16);
  const LuminanceImage away = renderLuminance(farScene(far, meshDir), 16);
  EXPECT_EQ(near.stats.rejectedSamples, 0u);
  EXPECT_EQ(away.stats.rejectedSamples, 0u);
  int differing = 0;
  double sum = 0.0;
  for (int y = 0; y < near.y.height; ++y)
    for (int x = 0; x < near.y.width; ++x) {
      differing += near.at(x, y) == away.at(x, y) ? 0 : 1;
      sum += near.at(x, y);
    }
  EXPECT_GT(sum, 0.0);
  EXPECT_EQ(differing, 0) << "of " << near.y.width * near.y.height << " pixels";
}

}  // namespace
}  // namespace camsim
