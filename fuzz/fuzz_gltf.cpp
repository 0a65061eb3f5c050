// libFuzzer harness: glTF bytes (.gltf JSON or .glb) → camsim::parseGltf
// (integrator/scene/gltf_document.h). Bad input must end in InputError; anything else
// (crash, sanitizer report, another exception, a document that breaks the contract below)
// is a finding. External files resolve against a directory that does not exist, so a
// fuzzed uri never reads the machine's files: every external buffer or image is "not found".
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_check.h"
#include "integrator/scene/gltf_document.h"
#include "sensor/base/input_error.h"

namespace {

// gltf_document.h: every primitive is a valid mesh (fuzz_check.h) with attributes of one
// per position; references are in range; animation keys are increasing and complete.
void checkDocument(const camsim::GltfDocument& doc) {
  for (const camsim::GltfMesh& mesh : doc.meshes)
    for (const camsim::GltfPrimitive& p : mesh.primitives) {
      camsim::fuzz::checkMesh(p.mesh);
      FUZZ_CHECK(p.mesh.uvs.empty() || p.mesh.uvs.size() == p.mesh.positions.size());
      FUZZ_CHECK(p.mesh.tangents.empty() || p.mesh.tangents.size() == p.mesh.positions.size());
      FUZZ_CHECK(p.mesh.colors.empty() || p.mesh.colors.size() == p.mesh.positions.size());
      for (const glm::vec3& c : p.mesh.colors)
        FUZZ_CHECK(c.r >= 0.0f && c.r <= 1.0f && c.g >= 0.0f && c.g <= 1.0f && c.b >= 0.0f &&
                   c.b <= 1.0f);
      FUZZ_CHECK(p.material < static_cast<int>(doc.materials.size()));
    }
  for (const camsim::GltfMaterial& m : doc.materials)
    for (const camsim::GltfTextureRef* t :
         {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture, &m.emissiveTexture})
      FUZZ_CHECK(t->image < static_cast<int>(doc.images.size()));
  for (const camsim::GltfImage& im : doc.images)
    FUZZ_CHECK(im.texels &&
               im.texels->values.size() == static_cast<std::size_t>(im.texels->width) *
                                               static_cast<std::size_t>(im.texels->height) * 4);
  for (const camsim::GltfNode& n : doc.nodes) {
    FUZZ_CHECK(n.mesh < static_cast<int>(doc.meshes.size()));
    FUZZ_CHECK(n.camera < static_cast<int>(doc.cameras.size()));
    for (int c : n.children) FUZZ_CHECK(c >= 0 && c < static_cast<int>(doc.nodes.size()));
  }
  for (const camsim::GltfAnimation& a : doc.animations)
    for (const camsim::GltfChannel& c : a.channels) {
      FUZZ_CHECK(c.node >= 0 && c.node < static_cast<int>(doc.nodes.size()));
      FUZZ_CHECK(!c.times.empty());
      for (std::size_t k = 1; k < c.times.size(); ++k) FUZZ_CHECK(c.times[k] > c.times[k - 1]);
      const std::size_t per =
          c.interpolation == camsim::GltfChannel::Interpolation::kCubicSpline ? 3 : 1;
      FUZZ_CHECK(c.values.size() == per * c.times.size());
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    checkDocument(camsim::parseGltf(bytes, "fuzz.gltf", "/nonexistent-camsim-fuzz-dir"));
  } catch (const camsim::InputError&) {
  }
  return 0;
}
