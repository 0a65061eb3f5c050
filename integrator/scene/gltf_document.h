// GltfDocument: a glTF 2.0 asset (.gltf with .bin and image files or data URIs, or .glb)
// read and checked into plain data, before anything is turned into camsim's scene parts
// (scene_loader_gltf.cpp does that). This module (gltf_document.cpp, gltf_read_materials.cpp,
// gltf_accessors.cpp, gltf_validate.cpp) is the only one that includes tinygltf and its
// JSON library; no header exposes them.
//
// What is kept, in glTF's own conventions (right-handed, +y up, metres, seconds):
//   nodes      matrix or TRS, children, mesh / camera / KHR_lights_punctual light
//   meshes     primitives as triangles (TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN; points
//              and lines are refused), POSITION, NORMAL, TANGENT, the TEXCOORD_n set the
//              material's textures read, COLOR_0, indices of any unsigned integer type (or
//              none), all read into MeshData in the node's space
//   materials  the metallic-roughness core, normal, occlusion and emissive textures (with
//              KHR_texture_transform), alpha mode, KHR_materials_emissive_strength,
//              _transmission, _ior
//   images     decoded texels (8-bit RGBA, or 16-bit) and, for an external file, its path
//   cameras    perspective and orthographic
//   lights     KHR_lights_punctual point, spot, directional
//   animations node translation / rotation / scale channels with their samplers
// Every reference, extent and value a later step reads is checked here: a malformed file
// throws InputError naming the file and the JSON path (key), e.g. `accessors[3].count`.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "integrator/geometry/mesh_io.h"
#include "integrator/textures/image_texture.h"

namespace camsim {

struct GltfTextureRef {
  int image = -1;  // index into GltfDocument::images; −1: no texture
  // Which TEXCOORD_n it reads: the textureInfo's texCoord, or KHR_texture_transform's.
  int texCoord = 0;
  double scale = 1.0;  // normalTexture.scale, occlusionTexture.strength
  std::string path;    // JSON path of the textureInfo, e.g. "materials[0].normalTexture"
  // KHR_texture_transform, in glTF's uv (v down the image), as the extension's text and
  // Khronos' viewers apply it: uv' = offset + R · (uv ⊙ uvScale), R = [cos r  sin r;
  // −sin r  cos r] (counter-clockwise as the image is seen).
  glm::dvec2 uvOffset{0.0}, uvScale{1.0};
  double uvRotation = 0.0;  // r, rad
};

struct GltfImage {
  std::string path;  // "images[2]"
  std::string name;
  std::filesystem::path file;  // the external file it came from; empty: embedded
  // Texels as stored (0..1, not yet decoded from sRGB), 4 channels RGBA.
  std::shared_ptr<const TextureImage> texels;
};

// The JSON paths, below a material's, of the extension values camsim reads.
inline constexpr const char* kEmissiveStrengthKey =
    ".extensions.KHR_materials_emissive_strength.emissiveStrength";
inline constexpr const char* kTransmissionKey =
    ".extensions.KHR_materials_transmission.transmissionFactor";
inline constexpr const char* kIorKey = ".extensions.KHR_materials_ior.ior";

struct GltfMaterial {
  enum class AlphaMode { kOpaque, kMask, kBlend };
  std::string name, path;
  glm::dvec4 baseColorFactor{1.0};
  GltfTextureRef baseColorTexture, metallicRoughnessTexture, normalTexture, occlusionTexture,
      emissiveTexture;
  double metallicFactor = 1.0, roughnessFactor = 1.0;
  glm::dvec3 emissiveFactor{0.0};
  double emissiveStrength = 1.0;  // KHR_materials_emissive_strength
  AlphaMode alphaMode = AlphaMode::kOpaque;
  double alphaCutoff = 0.5;
  bool doubleSided = false;
  double transmission = 0.0;                 // KHR_materials_transmission
  double ior = 1.5;                          // KHR_materials_ior
  std::vector<std::string> otherExtensions;  // names of extensions camsim does not read
  // The TEXCOORD_n set its textures read (camsim's meshes carry one set: textures reading
  // different sets all read the base colour's, noted).
  int texCoord = 0;
};

struct GltfPrimitive {
  std::string path;   // "meshes[1].primitives[0]"
  MeshData mesh;      // in the node's space; triangles; COLOR_0 in mesh.colors
  int material = -1;  // −1: glTF's default material
  // COLOR_0 is VEC4 with an alpha below 1 somewhere (camsim ignores vertex alpha).
  bool colorAlpha = false;
};

struct GltfMesh {
  std::string name, path;
  std::vector<GltfPrimitive> primitives;
};

struct GltfCamera {
  std::string name, path;
  bool perspective = true;
  double yfov = 0.0;         // rad
  double aspectRatio = 0.0;  // width / height; 0: not given
  double znear = 0.0, zfar = 0.0;
};

struct GltfLight {
  enum class Type { kPoint, kSpot, kDirectional };
  std::string name, path;
  Type type = Type::kPoint;
  glm::dvec3 color{1.0};   // linear Rec.709
  double intensity = 1.0;  // point, spot: cd; directional: lx
  double range = 0.0;      // m; 0: infinite
  double innerConeAngle = 0.0, outerConeAngle = 0.7853981633974483;  // rad
};

// The deepest node hierarchy read (a root is depth 1): the loader walks it recursively, and
// 2,000 levels overflowed the stack (found by probing); real assets nest a few dozen.
inline constexpr int kMaxGltfNodeDepth = 256;

struct GltfNode {
  std::string name, path;
  glm::dmat4 matrix{1.0};  // used when hasMatrix, else T·R·S
  bool hasMatrix = false;
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 scale{1.0};
  std::vector<int> children;
  int mesh = -1, camera = -1, light = -1;
  bool skinned = false, morphed = false;  // a skin / morph weights (refused when animated)

  glm::dmat4 local() const;  // parent ← node at rest
};

struct GltfChannel {
  enum class Path { kTranslation, kRotation, kScale, kWeights };
  enum class Interpolation { kLinear, kStep, kCubicSpline };
  std::string path;  // "animations[0].channels[1]"
  int node = -1;
  Path target = Path::kTranslation;
  Interpolation interpolation = Interpolation::kLinear;
  std::vector<double> times;  // s, strictly increasing
  // One value per key (xyz or quaternion xyzw); CUBICSPLINE: three per key (in-tangent,
  // value, out-tangent).
  std::vector<glm::dvec4> values;
};

struct GltfAnimation {
  std::string name, path;
  std::vector<GltfChannel> channels;
};

struct GltfDocument {
  std::filesystem::path file;
  std::vector<GltfNode> nodes;
  std::vector<GltfMesh> meshes;
  std::vector<GltfMaterial> materials;
  std::vector<GltfImage> images;
  std::vector<GltfCamera> cameras;
  std::vector<GltfLight> lights;
  std::vector<GltfAnimation> animations;
  std::vector<std::vector<int>> scenes;  // root nodes of each scene
  int defaultScene = 0;                  // `scene`, else 0
  // Files read besides `file` (buffers, images), each once.
  std::vector<std::filesystem::path> filesRead;
  // What was read but is not used or was changed (unknown extensions, texture sets, …).
  std::vector<std::string> notes;
};

// Reads and checks a .gltf or .glb file (by its magic bytes, not its extension).
GltfDocument readGltf(const std::filesystem::path& file);
// The same from bytes in memory (the fuzz harness); external files resolve against baseDir.
GltfDocument parseGltf(const std::string& bytes, const std::string& displayName,
                       const std::filesystem::path& baseDir);

// Internal: the structural check of the JSON before tinygltf reads it (gltf_validate.cpp):
// every index in range, every extent inside its view and buffer, every external file
// present. Throws InputError naming displayName and the JSON path.
void validateGltfJson(const std::string& json, const std::string& displayName,
                      const std::filesystem::path& baseDir, std::size_t glbBinBytes, bool isGlb);
// Internal: the bytes a buffer's data URI holds, decoded as tinygltf decodes it (base64
// characters up to the first '=' or other character, after one of the media types it
// reads: application/octet-stream, application/gltf-buffer, …); −1 if it reads none.
std::int64_t gltfDataUriBytes(const std::string& uri);

}  // namespace camsim
