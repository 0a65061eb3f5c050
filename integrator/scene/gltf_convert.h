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
  std::string where;        // "include[2] (file)": for notes
  SourceLocation location;  // the entry in the scene file, and its key path ("include[2]"),
  std::string key;          // for errors about its shapes found after loading
  std::string label;        // shape and material name prefix
  GltfDocument doc;
  glm::dmat4 worldFromAsset{1.0};  // the entry's placement (scene world ← asset)
  int scene = 0;                   // which of the asset's scenes
  // The animations that play, together from t = 0 (indices into doc.animations; all of
  // them unless the entry's `animation` chooses; empty: none).
  std::vector<int> animations;
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

// One animated node of a chain of animated nodes (outermost first) and the static
// transform before it: for the first, render ← the node's parent (the placement and the
// rest poses above it); for the others, the previous animated node's space (its residual
// scale included) ← this node's parent.
struct GltfChainLink {
  glm::dmat4 before{1.0};
  int node = -1;
};
// The render-space pose of the chain's last node over time, composed along the chain at
// every time step (gltf_motion.cpp), as camsim keyframes; the last node's constant
// non-uniform scale (if any) is returned in `residual`, to be applied to the geometry
// first. Throws InputError naming the node for what camsim's rigid motion cannot hold
// (a non-uniform animated scale, a pose that is not a similarity).
RigidMotion gltfChainMotion(const GltfInclude& inc, const std::vector<GltfChainLink>& chain,
                            glm::dmat4& residual);
// Nodes that the include's animations move.
std::vector<bool> gltfAnimatedNodes(const GltfInclude& inc);
// Channels that do not play because an earlier animation animates the same property of
// the same node, one note each.
std::vector<std::string> gltfAnimationNotes(const GltfInclude& inc);

}  // namespace camsim
