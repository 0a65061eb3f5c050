// SceneDescription: a loaded, validated scene as plain data in SI units (m, s, nm,
// W·m⁻²·sr⁻¹·nm⁻¹). The loader produces it from a scene file; Scene builds the renderable
// objects from it. Nothing here refers to a file format.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/textures/texture_encoding.h"

namespace camsim {
struct TextureImage;  // integrator/textures/image_texture.h
}

#include "integrator/camera/physical_camera.h"
#include "integrator/geometry/mesh_io.h"
#include "integrator/geometry/motion.h"
#include "integrator/materials/fresnel.h"
#include "integrator/materials/microfacet.h"
#include "sensor/base/enum_names.h"
#include "sensor/base/image.h"
#include "sensor/base/input_error.h"
#include "sensor/isp/isp_pipeline.h"
#include "sensor/model/exposure_control.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_spec.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

enum class SamplerKind { kIndependent, kSobol };
// The scene files' `render.sampler` values, also the sidecar's (sensor/base/enum_names.h).
template <>
struct EnumNames<SamplerKind> {
  static constexpr EnumName<SamplerKind> kTable[] = {{SamplerKind::kSobol, "sobol"},
                                                     {SamplerKind::kIndependent, "independent"}};
};
inline const char* samplerName(SamplerKind kind) {
  return enumName(kind).data();
}

// Ground truth from the first hit of the image's own camera samples (AOVs; the layers and
// their conventions: docs/output.md#ground-truth-aovs, integrator/render/aov_film.h).
enum class Aov : std::uint8_t {
  kDepth,
  kDistance,
  kPosition,
  kNormal,
  kAlbedo,
  kRoughness,
  kInstanceId,  // ID mattes (Cryptomatte) and the dominant id: the shape hit
  kClassId,     // the same for the shapes' `class:`
  kMaterialId,  // the same for their material
  kMotion,      // 2-D motion vectors and 3-D scene flow to the previous and next frame
  kValid,       // the fraction of the pixel's samples inside the camera model's image
  kAmodal,      // per labelled shape: its amodal and its visible coverage (mask_film.h)
  kOcclusion,   // which hit points the previous / next frame's camera does not see
  kBoundary,    // occlusion boundaries: pixels whose samples see several objects or depths
};
inline constexpr int kAovCount = 14;
// The scene's `render.aovs` names, also the sidecar's and the EXR layers'
// (sensor/base/enum_names.h).
template <>
struct EnumNames<Aov> {
  static constexpr EnumName<Aov> kTable[kAovCount] = {{Aov::kDepth, "depth"},
                                                      {Aov::kDistance, "distance"},
                                                      {Aov::kPosition, "position"},
                                                      {Aov::kNormal, "normal"},
                                                      {Aov::kAlbedo, "albedo"},
                                                      {Aov::kRoughness, "roughness"},
                                                      {Aov::kInstanceId, "instance_id"},
                                                      {Aov::kClassId, "class_id"},
                                                      {Aov::kMaterialId, "material_id"},
                                                      {Aov::kMotion, "motion"},
                                                      {Aov::kValid, "valid"},
                                                      {Aov::kAmodal, "amodal"},
                                                      {Aov::kOcclusion, "occlusion"},
                                                      {Aov::kBoundary, "boundary"}};
};
inline const char* aovName(Aov a) {
  return enumName(a).data();
}

struct RenderSettings {
  SamplerKind sampler = SamplerKind::kSobol;  // see integrator/sampling/sobol_sampler.h
  int spp = 64;                               // samples per pixel
  std::uint64_t seed = 0;                     // render seed
  int maxDepth = 16;                          // maximum number of scattering events on a path
  int rrDepth = 4;                            // Russian roulette starts after this many bounces
  std::vector<Aov> aovs;  // none by default: a plain render records no first hit
  // Passes (integrator/render/render.h): spp is then the first pass, the minimum.
  std::optional<double> targetError;  // estimated MRAE to stop at (error_estimate.h)
  std::optional<double> timeLimitS;   // s of render time not to pass
  int maxSpp = 1 << 20;               // the most samples per pixel passes may reach
  // Adaptive sampling (integrator/render/adaptive_sampling.h): on when a threshold is set;
  // spp is then the most samples a pixel gets (passes: the first pass).
  std::optional<double> adaptiveThreshold;  // estimated relative error to stop a pixel at
  int adaptiveMinSpp = 0;                   // even; 0 = automatic (adaptiveMinSppFor)
  bool guiding = false;                     // path guiding (integrator/render/path_guide.h)
  // The spectral control variate (integrator/render/spectral_control_variate.h).
  bool spectralControlVariate = true;
  bool passes() const { return targetError.has_value() || timeLimitS.has_value(); }
};

// A frame sequence (the scene's `frames` block): frame k (0-based) is sequence frame
// first + k, exposed from t_k = (first + k) / rate with the camera's shutter curve moved to
// start there, or a box of (angle / 360°) / rate when an angle is given. Keyframed motion
// runs on the same clock, so it spans the whole sequence.
struct FrameSequence {
  int count = 1;
  double rateHz = 24.0;
  int first = 0;
  std::optional<double> shutterAngleDeg;  // none: the camera's shutter, moved
  double startTime(int k) const { return (first + k) / rateHz; }
};

// A material input that may vary over the surface: a constant (spectrum or scalar), an
// image (EXR/PNG) or a procedural checkerboard. See integrator/textures/texture.h.
struct TextureDescription {
  enum class Kind { kConstant, kImage, kCheckerboard };
  Kind kind = Kind::kConstant;
  Spectrum value = Spectrum::constant(0.5);  // kConstant (scalar inputs: the constant's value)
  std::filesystem::path file;                // kImage
  // kImage: the decoded texels (shared, read once by the loader); null: read from `file`.
  std::shared_ptr<const TextureImage> image;
  // kImage: how texel values are encoded (texture_encoding.h), resolved by the loader: the
  // `encoding` key, else srgb for PNG and linear for EXR colour maps, raw for scalar maps.
  TextureEncoding encoding = TextureEncoding::kSrgb;
  Spectrum checkerA = Spectrum::constant(0.8), checkerB = Spectrum::constant(0.2);  // kCheckerboard
  float checks = 8.0f;                      // kCheckerboard: squares per unit of u and v
  glm::vec2 uvScale{1.0f}, uvOffset{0.0f};  // uv' = uv · scale + offset (kImage, kCheckerboard)
  // kImage: uv' = R(uvRotation) · (uv · scale) + offset, radians counter-clockwise in (u, v)
  // (integrator/textures/uv_transform.h); set by the glTF importer (KHR_texture_transform).
  float uvRotation = 0.0f;
  // kImage scalar maps: the channel read (0 = R, 1 = G, 2 = B, 3 = A), e.g. a glTF
  // metallic-roughness map packs roughness in G and metalness in B; −1: the default
  // reading of a scalar map (integrator/textures/image_texture.h).
  int channel = -1;

  static TextureDescription constant(double v) {
    TextureDescription t;
    t.value = Spectrum::constant(v);
    return t;
  }
};

struct MaterialDescription {
  enum class Type { kDiffuse, kConductor, kMirror, kDielectric, kPlastic, kMetallicRoughness };
  std::string name;
  Type type = Type::kDiffuse;
  // diffuse/plastic: diffuse reflectance ρ(λ); mirror: reflectance; conductor with
  // Schlick Fresnel: normal-incidence reflectance R0(λ). Dimensionless, in [0, 1].
  TextureDescription reflectance;
  // conductor/dielectric/plastic: microfacet α (dimensionless, ≥ 0; 0 = smooth). A
  // constant is given as a flat spectrum; only its value matters.
  TextureDescription roughness = TextureDescription::constant(0.0);
  float anisotropy = 0.0f;  // αx = α (1 + a), αy = α (1 − a); a in (−1, 1)
  MicrofacetDistribution distribution = MicrofacetDistribution::kGgx;
  MaskingModel masking = MaskingModel::kSmith;
  FresnelModel fresnel = FresnelModel::kExact;  // conductor
  Spectrum eta =
      Spectrum::constant(1.5);  // conductor η(λ); dielectric/plastic: index inside / outside
  Spectrum k = Spectrum::constant(0.0);  // conductor extinction k(λ)
  float specularWeight = 0.1f;           // plastic ks (kd = 1 − ks)
  // metallic_roughness (glTF 2.0 Appendix B): `reflectance` is the base colour, `roughness`
  // glTF's perceptual roughness r in [0, 1] (α = r²), `metallic` the metalness in [0, 1].
  TextureDescription metallic = TextureDescription::constant(0.0);
  // Tangent-space normal map (any material on a mesh with texture coordinates): linear RGB
  // texels c, n_tangent = normalize((2c − 1) · (scale, scale, 1)), glTF's convention: +x
  // along the tangent ∂p/∂u, +y along the bitangent ∂p/∂v with camsim's v (up the image).
  std::optional<TextureDescription> normalMap;
  float normalScale = 1.0f;
  // Alpha cut-out (glTF alphaMode MASK; BLEND is treated as MASK at 0.5): a hit whose alpha
  // = factor · texel(channel, usually 3 of the base-colour image) is below `cutoff` is not a
  // hit, for camera, bounce and shadow rays alike.
  struct AlphaCutout {
    std::optional<TextureDescription> texture;  // none: alpha = factor everywhere
    float factor = 1.0f;
    float cutoff = 0.5f;
  };
  std::optional<AlphaCutout> alphaCutout;
};
// The scene's material `type` names (sensor/base/enum_names.h).
template <>
struct EnumNames<MaterialDescription::Type> {
  using T = MaterialDescription::Type;
  static constexpr EnumName<T> kTable[] = {
      {T::kDiffuse, "diffuse"},     {T::kMirror, "mirror"},
      {T::kConductor, "conductor"}, {T::kDielectric, "dielectric"},
      {T::kPlastic, "plastic"},     {T::kMetallicRoughness, "metallic_roughness"}};
};

// Lights that are not shapes (`lights:` in the scene file; units in docs/scene-format.md).
// World up is +y (as the scenes' cameras): the loader builds `direction` from
// elevation/azimuth and `worldFromLight` from the rotation about +y.
struct LightDescription {
  enum class Kind { kPoint, kSpot, kDistant, kEnvironment };
  Kind kind = Kind::kPoint;
  std::string label;  // for messages
  // point/spot:  radiant intensity I(λ), W·sr⁻¹·nm⁻¹ (spot: on its axis)
  // distant:     spectral irradiance E(λ) on a plane facing the light, W·m⁻²·nm⁻¹
  // environment: dimensionless spectral scale s(λ) of the map's uplifted texels (a texel
  //              (1, 1, 1) is D65/Σ D65 ȳ W·m⁻²·sr⁻¹·nm⁻¹, luminance 683 cd/m², at s = 1)
  Spectrum spectrum = Spectrum::constant(0.0);
  glm::vec3 position{0.0f};                // point/spot, m
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // spot axis / the way sunlight travels (unit)
  float coneAngle = 0.5f;                  // spot: half-angle where the light ends, rad
  float falloffStart = 0.4f;  // spot: half-angle where the smooth falloff begins, rad (≤ coneAngle)
  float angularDiameter = 0.0f;  // distant: apparent diameter of the disc, rad (0 = delta)
  std::filesystem::path file;    // environment: lat-long EXR (linear Rec.709 R, G, B)
  // environment: the map's texels as loaded (shared, read once by the loader); null: the
  // factory reads `file`.
  std::shared_ptr<const Image> image;
  // environment: rotation, map space → world. Map space has +z at the zenith (row 0);
  // see integrator/lights/environment_light.h for the lat-long mapping.
  glm::dmat3 worldFromLight{1.0};
};

struct EmissionDescription {
  Spectrum radiance;  // L_e(λ), W·m⁻²·sr⁻¹·nm⁻¹
  bool twoSided = false;
};

struct ShapeDescription {
  enum class Kind { kMesh, kSphere };
  Kind kind = Kind::kMesh;
  std::string label;  // for messages: the user's name or "shapes[i]"; the instance's id name
  // Where the scene file wrote it, for errors found after loading (its reach, placement,
  // cut-out): the entry's line and key path ("shapes[2]", "shapes[2].instances[1]",
  // "include[0]"); an empty file: a description built in code (then the scene file, and the
  // label as the key).
  SourceLocation where;
  std::string key;
  // `class:` — the semantic class: its name (an integer's decimal text, or a word) and, for
  // an integer, its number (≥ 1); empty name: unlabelled (class 0, as the background).
  std::string className;
  std::optional<std::uint32_t> classNumber;
  int material = -1;  // index into SceneDescription::materials; -1 = black (reflects nothing)
  std::optional<EmissionDescription> emission;
  MeshData mesh;           // kMesh, object space (m)
  glm::vec3 centre{0.0f};  // kSphere, object space (m)
  float radius = 0.0f;     // kSphere (m)
  RigidMotion motion;      // object → world over time; empty = identity
  // kMesh instanced (glTF nodes sharing a mesh, the YAML `instances:` list): when set, the
  // geometry is this mesh in its own object space, stored once however many shapes point
  // to it, and `mesh` is empty. It is placed by motion.at(t) · placement (object → render
  // space): `placement` is any invertible affine matrix (non-uniform scale and mirroring
  // included); a static instance has an empty motion.
  std::shared_ptr<const MeshData> sharedMesh;
  glm::dmat4 placement{1.0};
  // kMesh: the model frame of the object pose (integrator/capture/object_poses.h): the
  // mesh's coordinates (`mesh`, or `sharedMesh`) are objectFromModel · (model coordinates),
  // so that the model is the mesh as its source gives it and the rest is pose. The loader
  // sets: a mesh file's `translate` (minus the render shift of a static shape), the render
  // shift of inline vertices and rectangles, a glTF primitive's node transform. Identity
  // for descriptions built in code.
  glm::dmat4 objectFromModel{1.0};
};

// `exports:` — dataset layouts written beside a capture's files (docs/output.md): each
// named once here, parsed by the loader.
enum class ExportFormat : std::uint8_t {
  kBop,    // the BOP 6-DoF pose layout under bop/ (integrator/capture/bop_writer.h)
  kKitti,  // the KITTI object layout under kitti/ (integrator/capture/kitti_writer.h)
};
template <>
struct EnumNames<ExportFormat> {
  static constexpr EnumName<ExportFormat> kTable[] = {{ExportFormat::kBop, "bop"},
                                                      {ExportFormat::kKitti, "kitti"}};
};
inline const char* exportFormatName(ExportFormat f) {
  return enumName(f).data();
}

// The camera keys a sensor's pixel pitch and fill factor decide (refused beside a scene's
// sensor, replaced by a sensor override with a note).
inline constexpr std::array<const char*, 3> kSensorGeometryKeys = {
    "sensor_width_mm", "sensor_height_mm", "fill_factor"};

// `sensor:` — the camera's sensor and how it is exposed and read out.
struct SensorSettings {
  SensorSpec spec;
  double iso = 100.0;
  NoiseMode noise = NoiseMode::kFull;
  std::uint64_t noiseSeed = 0;
  std::uint64_t frame = 0;
  std::optional<AutoExposure> autoExposure;
  std::vector<double> bracketEv;  // exposure offsets in stops; empty: one exposure

  // The longest bracket's exposure over the scene's: 2^max(bracket_ev, 0) (a sequence's
  // frame must hold it: frameTimingProblem, and auto-exposure's hold in capture()).
  double longestBracketFactor() const {
    double longest = 1.0;
    for (const double ev : bracketEv) longest = std::max(longest, std::exp2(ev));
    return longest;
  }
};
// A bracketed frame's file-name suffix, "_ev" and the offset as %+g (6 significant digits):
// NAME_ev+1.dng. The loader refuses offsets that give the same suffix.
std::string bracketSuffix(double ev);

struct SceneDescription {
  std::string sourceFile;   // what it was loaded from ("<default>" for the embedded scene)
  std::string sourceFnv1a;  // FNV-1a 64 of the scene text (sensor/base/fnv1a.h)
  // Every other file the loader read for it, in the order first read, each once: meshes,
  // textures, environment maps, spectral tables (also named metals and glasses from
  // luts/spectra), the sensor description and its tables. Named illuminants and the CIE
  // observer are built into camsim (sensor/spectra/spectral_data.h) and not listed. Building a
  // Scene from it reads no other file.
  std::vector<std::filesystem::path> inputFiles;
  // Render space: every position below is relative to this point of the scene file's
  // world (m) — the camera's rest position — so that scenes far from the world origin
  // keep single-precision accuracy near the camera (world = render + renderOrigin).
  glm::dvec3 renderOrigin{0.0};
  std::string name;  // output base name
  PhysicalCameraParams camera;
  RenderSettings render;
  std::vector<MaterialDescription> materials;
  std::vector<ShapeDescription> shapes;
  std::vector<LightDescription> lights;
  std::optional<SensorSettings> sensor;  // none: the film records CIE XYZ only
  IspSettings isp;                       // raw → picture (scenes with a sensor)
  // Where the scene file sets the keys that a stage after loading may still refuse (the
  // white balance of the rendered raw: sensor, isp, isp.white_balance, isp.region; a sensor
  // override: camera.sensor_width_mm, camera.sensor_height_mm, camera.fill_factor), so that
  // its error names the file, line and key. Empty for descriptions built in code.
  std::map<std::string, SourceLocation> keyPlaces;
  std::optional<FrameSequence> frames;  // none: one capture at the camera's shutter
  std::vector<ExportFormat> exports;    // `exports:`, in the file's order, each once
  bool exportsTo(ExportFormat f) const {
    for (ExportFormat e : exports)
      if (e == f) return true;
    return false;
  }
  // What the loader left out or changed, one sentence each naming the file and the JSON
  // path (or line) and key: features of imported assets that camsim ignores or approximates
  // (docs/scene-format.md lists them). The CLI prints them; the sidecar lists them as
  // "import_notes".
  std::vector<std::string> notes;

  // Every frame's shutter before it is moved to the frame's start: the camera's, or with a
  // shutter angle a box of (angle / 360°) / rate from 0 that keeps the camera's readout (a
  // rolling shutter's row_time; found by probing: it was dropped, the frames read out global).
  Shutter frameShutter() const {
    if (!frames || !frames->shutterAngleDeg) return camera.shutter;
    return Shutter::trapezoid(0.0, *frames->shutterAngleDeg / 360.0 / frames->rateHz, 0.0, 0.0,
                              camera.shutter.type(), camera.shutter.rowTime());
  }
  // The camera of sequence frame k (0-based): frameShutter() moved to the frame's start.
  PhysicalCameraParams frameCamera(int k) const {
    PhysicalCameraParams c = camera;
    if (!frames) return c;
    c.shutter = frameShutter();
    c.shutter = c.shutter.shifted(frames->startTime(k) - c.shutter.open());
    return c;
  }

  // Drops the decoded texels of image textures and environment maps. A Scene built from
  // this description keeps them in its own form, so a render need not hold both (an 8k RGB
  // texture is 0.8 GB of floats); a Scene built afterwards reads the files again.
  // Texels that came from no file (a glTF asset's decoded and converted images) are kept.
  void releaseDecodedImages() {
    auto release = [](TextureDescription& t) {
      if (!t.file.empty()) t.image.reset();
    };
    for (MaterialDescription& m : materials) {
      release(m.reflectance);
      release(m.roughness);
      release(m.metallic);
      if (m.normalMap) release(*m.normalMap);
      if (m.alphaCutout && m.alphaCutout->texture) release(*m.alphaCutout->texture);
    }
    for (LightDescription& l : lights) l.image.reset();
  }
};

}  // namespace camsim
