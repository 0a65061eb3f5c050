// Memory of instancing (integrator/geometry/mesh_instance.h, embree_scene.h): 1,000
// instances of the Stanford bunny (69,451 triangles, scenes/meshes/) cost the memory of one
// bunny plus a constant per instance. Counted: what Embree's memory monitor reports
// (EmbreeScene::embreeBytes() after the build, embreePeakBytes() during it: the BVHs, and
// for instances Embree's instance geometry and the top-level BVH over them) plus the
// arrays the meshes hold (positions, indices, stored face normals, at their capacity) plus
// the MeshInstance objects themselves.
#include <gtest/gtest.h>

#include <random>

#include "integrator/geometry/embree_scene.h"
#include "integrator/geometry/mesh_instance.h"
#include "tests/integrator/instance_test_support.h"

namespace camsim {
namespace {

// The stated per-instance cost, bytes: sizeof(MeshInstance) (≈ 0.3 kB) plus Embree's
// instance and its share of the top-level BVH (measured ≈ 0.3–0.5 kB; see
// docs/performance.md). The test records the measured cost as a property.
constexpr double kBytesPerInstance = 1024.0;

std::int64_t arrayBytes(const TriangleMesh& m) {
  return static_cast<std::int64_t>(
      m.positions().capacity() * sizeof(glm::vec3) +
      m.indices().capacity() * sizeof(std::uint32_t) + m.normals().capacity() * sizeof(glm::vec3) +
      m.uvs().capacity() * sizeof(glm::vec2) + m.faceNormals().capacity() * sizeof(glm::vec3));
}

struct Bytes {
  std::int64_t held = 0;  // after the build
  std::int64_t peak = 0;  // during it
};

TEST(MeshInstanceMemory, ThousandBunniesCostOneBunnyPlusAConstantEach) {
  const MeshData bunny =
      readObj(std::filesystem::path(CAMSIM_SOURCE_DIR) / "scenes/meshes/stanford-bunny.obj");
  ASSERT_EQ(bunny.indices.size(), 3u * 69451u);
  Bytes one, thousand;
  {
    std::vector<std::unique_ptr<Shape>> shapes;
    shapes.push_back(std::make_unique<TriangleMesh>(bunny.positions, bunny.normals, bunny.indices,
                                                    TimeSteps{}, bunny.uvs));
    const EmbreeScene scene(shapes, 0.0, 1.0);
    const std::int64_t arrays = arrayBytes(dynamic_cast<const TriangleMesh&>(*shapes[0]));
    one = {scene.embreeBytes() + arrays, scene.embreePeakBytes() + arrays};
  }
  {
    const std::shared_ptr<const TriangleMesh> shared = test::staticMeshOf(bunny);
    std::vector<std::unique_ptr<Shape>> shapes;
    std::mt19937 rng(8);
    for (int i = 0; i < 1000; ++i)
      shapes.push_back(std::make_unique<MeshInstance>(
          shared, std::vector<glm::dmat4>{test::randomPlacement(rng, 10.0)}, TimeSteps{}));
    const EmbreeScene scene(shapes, 0.0, 1.0);
    const std::int64_t own =
        arrayBytes(*shared) + 1000 * static_cast<std::int64_t>(sizeof(MeshInstance));
    thousand = {scene.embreeBytes() + own, scene.embreePeakBytes() + own};
  }
  const double perInstance = static_cast<double>(thousand.held - one.held) / 999.0;
  const double perInstancePeak = static_cast<double>(thousand.peak - one.peak) / 999.0;
  RecordProperty("one_bunny_bytes", std::to_string(one.held));
  RecordProperty("one_bunny_peak_bytes", std::to_string(one.peak));
  RecordProperty("bytes_per_instance", std::to_string(perInstance));
  RecordProperty("peak_bytes_per_instance", std::to_string(perInstancePeak));
  RecordProperty("sizeof_mesh_instance", std::to_string(sizeof(MeshInstance)));
  EXPECT_LT(static_cast<double>(thousand.held), 1.2 * one.held + 1000 * kBytesPerInstance);
  EXPECT_LT(static_cast<double>(thousand.peak), 1.2 * one.peak + 1000 * kBytesPerInstance);
  // Against 1,000 copies, whose cost is a thousand bunnies' (not built: ≈ 8 GB).
  EXPECT_LT(static_cast<double>(thousand.held), 0.01 * 1000.0 * one.held);
}

}  // namespace
}  // namespace camsim
