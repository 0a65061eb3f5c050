// Internal pieces of the scene loader shared between its files (not a public API).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include <glm/vec3.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/geometry/motion.h"
#include "integrator/scene/scene_description.h"
#include "integrator/scene/scene_spectra.h"
#include "sensor/base/yaml_reader.h"

namespace camsim {

// Geometry is stored in single precision: a point finite as a double can still overflow.
glm::vec3 toPoint(const YamlValue& where, const glm::dvec3& v);
// A positive length stored in single precision: it must not underflow to 0.
float positiveFloat(const YamlValue& where, double v);
// `camera:` → camera parameters (see docs/scene-format.md).
PhysicalCameraParams parseCamera(YamlMap map, const TableSearch& search);
// `camera.lens` (scene_loader_lens.cpp): the prescription and its f-number and focus
// distance into c.lens, with the thin-lens stand-in's focal length and f-number; refuses the
// thin lens's keys in `camera` beside it. Parsed after camera.aperture (its blades shape the stop).
void parseCameraLens(const YamlValue& value, const YamlMap& camera, const TableSearch& search,
                     PhysicalCameraParams& c);

// `sensor:` → sensor settings; sets the camera's sensor size and fill factor from the
// sensor's pixel pitch (cameraMap: the camera's keys, to reject conflicting ones).
SensorSettings parseSensorSettings(YamlMap map, const std::filesystem::path& baseDir,
                                   const YamlValue& camera, PhysicalCameraParams& cameraParams);
// `isp:` → image-pipeline settings (white balance, demosaic).
// keyPlaces: where the isp keys are (SceneDescription::keyPlaces); the region and grey world
// are checked against the sensor's CFA and the image's resolution (px).
IspSettings parseIspSettings(YamlMap map, const SensorSpec& sensor, glm::ivec2 resolution,
                             std::map<std::string, SourceLocation>& keyPlaces);
// A material input that may be a texture (integrator/scene/scene_loader_textures.cpp):
// reflectance: a spectrum (see scene_spectra.h), {texture: …} or {checkerboard: …};
// roughness: a number ≥ 0 (≤ 1000) or {texture: …} or {checkerboard: …}; fraction: the
// same with numbers in [0, 1] (metallic, perceptual roughness); normal map: {texture: …}
// only, an RGB image read raw. Scalar image textures (roughness, fraction) take `channel`.
enum class TextureUse { kReflectance, kRoughness, kFraction, kNormalMap };
TextureDescription parseTexture(const YamlValue& v, TextureUse use, const TableSearch& search,
                                const std::filesystem::path& baseDir);
// `materials:` entry → material description (integrator/scene/scene_loader_materials.cpp).
MaterialDescription parseMaterial(const std::string& name, YamlMap map, const TableSearch& search,
                                  const std::filesystem::path& baseDir);
// Twice the total area of a mesh, from its single-precision positions (scene_loader.cpp).
double meshArea2(const MeshData& mesh);
// The materials a scene imported from mesh files (OBJ .mtl), shared by the shapes naming the
// same file: scene name "FILE:NAME" (FILE: the shape's `file:` as written) → index into
// SceneDescription::materials; and the map_Kd images decoded so far.
struct ImportedMaterials {
  std::map<std::string, int> index;
  std::map<std::filesystem::path, std::shared_ptr<const TextureImage>> images;
};
// A mesh shape without `material:` whose OBJ has usemtl groups (scene_loader_mtl.cpp): reads
// its mtllib files (relative to objPath's folder), maps each material used to a camsim
// material (appended to scene.materials once per scene name, never clashing with
// sceneMaterials) and returns one shape per material, each with the vertices it uses
// (label "LABEL/NAME" when there are several). Ignored and approximated .mtl statements are
// appended to scene.notes. InputError: a missing .mtl or map_Kd file, an unknown usemtl,
// triangles without a material on a shape that does not emit, a malformed .mtl.
std::vector<ShapeDescription> splitByFileMaterials(
    ShapeDescription shape, const std::filesystem::path& objPath, const YamlValue& file,
    ImportedMaterials& imported, const std::map<std::string, int>& sceneMaterials,
    const TableSearch& search, SceneDescription& scene);
// 16 numbers, row by row, with last row [0, 0, 0, 1] and a translation float can hold: the
// matrix (scene_loader_camera.cpp). Callers check the linear part (orthonormal, invertible).
glm::dmat4 parseAffineMatrix(const YamlValue& m);
// A placement world ← object from a map's `matrix` (16 numbers, row by row, affine,
// invertible) or `translate` (m), `rotate` ({axis, angle_deg}), `scale` (a number or
// [sx, sy, sz], non-zero; negative mirrors): T · R · S (scene_loader_instances.cpp).
glm::dmat4 parsePlacement(YamlMap& map);
// `{axis: [x, y, z], angle_deg: a}` → the rotation (the axis need not be unit; not zero).
glm::dquat parseRotation(const YamlValue& value);
// `motion:` keyframes; `forCamera` forbids scale. Each `translate` minus `origin` (in
// double): shapes pass the render origin (their keyframes are world positions), the
// camera zero (its keyframes are offsets from its rest position).
RigidMotion parseMotion(const YamlValue& value, bool forCamera, const glm::dvec3& origin);
// A shape's `class:` (a name, or an integer ≥ 1 that is the class number) into s.
void parseShapeClass(const YamlValue& c, ShapeDescription& s);
// A mesh shape's `instances:` (scene_loader_instances.cpp): one ShapeDescription per item,
// all sharing `shape`'s mesh (moved into one MeshData, object space) and its material,
// emission and class (an item may give its own name, class and material: `materials` maps
// names to indices). Each is placed by its `translate`/`rotate`/`scale` or `matrix`, then
// its `motion`; translations are world positions, shifted into render space by `origin`.
void parseInstances(const YamlValue& list, ShapeDescription shape,
                    const std::map<std::string, int>& materials, const glm::dvec3& origin,
                    std::vector<ShapeDescription>& out);
// `alpha_cutout:` of a material (scene_loader_materials.cpp): {alpha: scalar texture,
// factor, cutoff}.
MaterialDescription::AlphaCutout parseAlphaCutout(const YamlValue& value, const TableSearch& search,
                                                  const std::filesystem::path& baseDir);
// `lights:` → point, spot, distant and environment lights (scene_loader_lights.cpp);
// positions are shifted into render space (world − renderOrigin), files resolve against
// baseDir.
std::vector<LightDescription> parseLights(const YamlValue& lights, const TableSearch& search,
                                          const std::filesystem::path& baseDir,
                                          const glm::dvec3& renderOrigin);

// `include:` entries (glTF assets, scene_loader_gltf.cpp): each file read and checked.
struct GltfInclude;
std::vector<GltfInclude> parseGltfIncludes(const YamlValue& list,
                                           const std::filesystem::path& baseDir,
                                           TableSearch& search);
// `camera: {gltf: {include, camera}}`: the camera's pose from the glTF camera's node;
// returns its vertical field of view (rad), which sets the focal length on the sensor's
// height once the sensor is known: f = (h/2) / tan(yfov/2).
double applyGltfCamera(const YamlValue& spec, const std::vector<GltfInclude>& includes,
                       PhysicalCameraParams& camera, std::vector<std::string>& notes);
// The includes' shapes, materials and lights, appended to scene (render space).
void addGltfIncludes(std::vector<GltfInclude>& includes, SceneDescription& scene);

}  // namespace camsim
