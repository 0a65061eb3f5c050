// A glTF material's values: a mistyped one is refused by its JSON path (tinygltf alone drops
// it for its default silently: roughnessFactor "x" rendered as roughness 1), and a value out
// of range names the whole path, extensions included (integrator/scene/gltf_validate.cpp,
// gltf_read_materials.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "integrator/scene/gltf_document.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/scene/gltf_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

// A one-triangle file whose material 0 is `material`; the key of the InputError reading it
// raises ("" if it reads).
std::string refusedKey(const std::string& material) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const test::TempDir tmp;
  const fs::path dir = tmp.path();
  test::writeText(
      dir / "tri.gltf",
      b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
             R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"materials":[)" +
             material + "]"));
  try {
    readGltf(dir / "tri.gltf");
  } catch (const InputError& e) {
    EXPECT_EQ(fs::path(e.where().file).filename(), "tri.gltf") << e.what();
    return e.key();
  }
  return "";
}

TEST(GltfMaterialValues, MistypedValuesAreRefusedByTheirJsonPath) {
  const struct {
    const char* material;
    const char* key;
  } cases[] = {
      {R"({"pbrMetallicRoughness":{"roughnessFactor":"x"}})",
       "materials[0].pbrMetallicRoughness.roughnessFactor"},
      {R"({"pbrMetallicRoughness":{"metallicFactor":[1]}})",
       "materials[0].pbrMetallicRoughness.metallicFactor"},
      {R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,1]}})",
       "materials[0].pbrMetallicRoughness.baseColorFactor"},
      {R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,"1",1]}})",
       "materials[0].pbrMetallicRoughness.baseColorFactor"},
      {R"({"emissiveFactor":"bright"})", "materials[0].emissiveFactor"},
      {R"({"alphaCutoff":null})", "materials[0].alphaCutoff"},
      {R"({"alphaMode":1})", "materials[0].alphaMode"},
      {R"({"doubleSided":"yes"})", "materials[0].doubleSided"},
      {R"({"extensions":[]})", "materials[0].extensions"},
      {R"({"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":"9"}}})",
       "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength"},
      {R"({"extensions":{"KHR_materials_transmission":{"transmissionFactor":true}}})",
       "materials[0].extensions.KHR_materials_transmission.transmissionFactor"},
      {R"({"extensions":{"KHR_materials_ior":7}})", "materials[0].extensions.KHR_materials_ior"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.material);
    EXPECT_EQ(refusedKey(c.material), c.key);
  }
  // Well-typed values and a material without any still read.
  EXPECT_EQ(refusedKey(R"({"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,0.5,1],)"
                       R"("roughnessFactor":0.3},"emissiveFactor":[0,0,0],"alphaMode":"MASK",)"
                       R"("alphaCutoff":0.4,"doubleSided":true,"extensions":)"
                       R"({"KHR_materials_ior":{"ior":1.33}}})"),
            "");
  EXPECT_EQ(refusedKey("{}"), "");
}

TEST(GltfMaterialValues, OutOfRangeValuesNameTheWholePath) {
  const struct {
    const char* material;
    const char* key;
  } cases[] = {
      {R"({"pbrMetallicRoughness":{"roughnessFactor":-0.5}})",
       "materials[0].pbrMetallicRoughness.roughnessFactor"},
      {R"({"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":-1}}})",
       "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength"},
      {R"({"extensions":{"KHR_materials_transmission":{"transmissionFactor":-1}}})",
       "materials[0].extensions.KHR_materials_transmission.transmissionFactor"},
      {R"({"extensions":{"KHR_materials_ior":{"ior":0.5}}})",
       "materials[0].extensions.KHR_materials_ior.ior"},
      // glTF bounds these to [0, 1]; above it they were clamped silently.
      {R"({"pbrMetallicRoughness":{"roughnessFactor":2}})",
       "materials[0].pbrMetallicRoughness.roughnessFactor"},
      {R"({"pbrMetallicRoughness":{"metallicFactor":1.5}})",
       "materials[0].pbrMetallicRoughness.metallicFactor"},
      {R"({"extensions":{"KHR_materials_transmission":{"transmissionFactor":1.01}}})",
       "materials[0].extensions.KHR_materials_transmission.transmissionFactor"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.material);
    EXPECT_EQ(refusedKey(c.material), c.key);
  }
}

}  // namespace
}  // namespace camsim
