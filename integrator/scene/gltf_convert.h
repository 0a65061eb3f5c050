// Internal to the scene loader: a glTF document's materials, lights and animation turned
// into camsim's scene parts (scene_loader_gltf.cpp, gltf_materials.cpp, gltf_motion.cpp).
// Conventions and every mapping: docs/scene-format.md, "glTF assets".
#pragma once

#include <map>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "integrator/geometry/motion.h"
#include "integrator/scene/gltf_document.h"
#include "integrator/scene/scene_description.h"

namespace camsim {

// One `include:` entry, resolved.
struct GltfInclude {
  std::string where;  // "include[2] (file)": for notes
  std::string label;  // shape and material name prefix
  GltfDocument doc;
  glm::dmat4 worldFromAsset{1.0};  // the entry's placement (scene world ← asset)
  int scene = 0;                   // which of the asset's scenes
  int animation = -1;              // which animation plays; −1: none
  bool lights = true;
  double emissiveLuminance = 100.0;  // cd/m² of emissive (1, 1, 1)
  std::string className;
  std::optional<std::uint32_t> classNumber;
};

// The glTF materials as camsim materials, appended to scene.materials; returns the index of
// each. Notes go to scene.notes.
std::vector<int> addGltfMaterials(const GltfInclude& inc, SceneDescription& scene);
// glTF's default material (for primitives without one), appended; returns its index.
int addGltfDefaultMaterial(const GltfInclude& inc, SceneDescription& scene);
// The emission of a glTF material, if it emits (emissiveFactor · strength · texture mean).
std::optional<EmissionDescription> gltfEmission(const GltfInclude& inc, int material,
                                                SceneDescription& scene);
// A KHR_lights_punctual light at renderFromNode (light −z is its direction).
LightDescription gltfLight(const GltfInclude& inc, const GltfLight& light,
                           const glm::dmat4& renderFromNode, SceneDescription& scene);

// The local transform of node `node` over time under the include's animation, as camsim
// keyframes of  renderFromParent · local(t)  (renderFromParent a similarity: uniform scale),
// with the node's constant non-uniform scale (if any) returned in `residual` to be applied
// to the geometry first. Throws InputError naming the node for what camsim's rigid motion
// cannot hold (non-uniform or non-similar animated transforms).
RigidMotion gltfNodeMotion(const GltfInclude& inc, int node, const glm::dmat4& renderFromParent,
                           glm::dmat4& residual);
// Nodes that the include's animation moves.
std::vector<bool> gltfAnimatedNodes(const GltfInclude& inc);

}  // namespace camsim
