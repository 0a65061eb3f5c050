// Tests for integrator/capture/annotations.cpp with instanced meshes: an instance's
// projected 3-D box is the box of its placed vertices (the shared mesh through its
// placement, then its motion), the one its baked copy gets.
#include "integrator/capture/annotations.h"

#include <gtest/gtest.h>

#include "integrator/scene/scene_loader.h"
#include "tests/integrator/instance_test_support.h"

namespace camsim {
namespace {

TEST(Annotations, AnInstancesBoxIsItsBakedCopysBox) {
  CaptureResult r;
  r.description = loadSceneFromText(
      "camera: {position: [0, 0, -4], look_at: [0, 0, 0], resolution: [8, 8]}\n"
      "materials: {m: {type: diffuse}}\n"
      "shapes:\n"
      "  - type: mesh\n"
      "    class: blob\n"
      "    material: m\n"
      "    vertices: [[-0.2, -0.1, 0], [0.3, -0.1, 0.1], [0, 0.25, -0.1]]\n"
      "    faces: [[0, 1, 2]]\n"
      "    instances:\n"
      "      - {matrix: [0.5, 1.2, 0, 0.3,  -1, 0.4, 0, -0.2,  0, 0, 2, 0.5,  0, 0, 0, 1]}\n"
      "      - {translate: [-0.5, 0.3, 0], rotate: {axis: [0, 0, 1], angle_deg: 40},\n"
      "         motion: [{time: 0, translate: [0.1, 0, 0]}]}\n",
      "boxes.yaml", ".");
  ASSERT_EQ(r.description.shapes.size(), 2u);
  // Both instances cover some pixels of the instance-id layer (ids are shape index + 1).
  r.aovs = Image(8, 8, {"instance.id"});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) r.aovs.at(x, y, 0) = x < 4 ? 1.0f : 2.0f;
  CaptureResult copies = r;
  for (ShapeDescription& s : copies.description.shapes) {
    s.mesh = test::baked(*s.sharedMesh, s.placement);
    s.sharedMesh.reset();
    s.placement = glm::dmat4(1.0);
  }
  const std::vector<InstanceAnnotation> a = annotateFrame(r), b = annotateFrame(copies);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    ASSERT_TRUE(a[i].bbox3d && b[i].bbox3d) << i;
    for (int k = 0; k < 4; ++k) EXPECT_NEAR((*a[i].bbox3d)[k], (*b[i].bbox3d)[k], 1e-4) << i;
    EXPECT_GT((*a[i].bbox3d)[2], 0.5) << i;  // a box of some pixels, not a point
  }
  // The two instances are in different places: different boxes.
  EXPECT_GT(std::abs((*a[0].bbox3d)[0] - (*a[1].bbox3d)[0]), 0.5);
}

}  // namespace
}  // namespace camsim
