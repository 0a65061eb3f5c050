// SceneDescription: a loaded, validated scene as plain data in SI units (m, s, nm,
// W·m⁻²·sr⁻¹·nm⁻¹). The loader produces it from a scene file; Scene builds the renderable
// objects from it. Nothing here refers to a file format.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/mesh_io.h"
#include "integrator/motion.h"
#include "integrator/physical_camera.h"
#include "sensor/exposure_control.h"
#include "sensor/isp_pipeline.h"
#include "sensor/sensor_model.h"
#include "sensor/sensor_spec.h"
#include "sensor/spectrum.h"

namespace camsim {

enum class SamplerKind { kIndependent, kSobol };

struct RenderSettings {
  SamplerKind sampler = SamplerKind::kSobol;  // see integrator/sobol_sampler.h
  int spp = 64;             // samples per pixel
  std::uint64_t seed = 0;   // render seed
  int maxDepth = 16;        // maximum number of scattering events on a path
  int rrDepth = 3;          // Russian roulette starts after this many bounces
};

struct MaterialDescription {
  std::string name;
  Spectrum reflectance;  // diffuse reflectance ρ(λ), dimensionless
};

struct EmissionDescription {
  Spectrum radiance;      // L_e(λ), W·m⁻²·sr⁻¹·nm⁻¹
  bool twoSided = false;
};

struct ShapeDescription {
  enum class Kind { kMesh, kSphere };
  Kind kind = Kind::kMesh;
  std::string label;  // for messages: the user's name or "shapes[i]"
  int material = -1;  // index into SceneDescription::materials; -1 = black (reflects nothing)
  std::optional<EmissionDescription> emission;
  MeshData mesh;              // kMesh, object space (m)
  glm::vec3 centre{0.0f};     // kSphere, object space (m)
  float radius = 0.0f;        // kSphere (m)
  RigidMotion motion;         // object → world over time; empty = identity
};

// `sensor:` — the camera's sensor and how it is exposed and read out.
struct SensorSettings {
  SensorSpec spec;
  double iso = 100.0;
  NoiseMode noise = NoiseMode::kFull;
  std::uint64_t noiseSeed = 0;
  std::uint64_t frame = 0;
  std::optional<AutoExposure> autoExposure;
  std::vector<double> bracketEv;  // exposure offsets in stops; empty: one exposure
};

struct SceneDescription {
  std::string sourceFile;  // what it was loaded from ("<default>" for the embedded scene)
  std::string name;        // output base name
  PhysicalCameraParams camera;
  RenderSettings render;
  std::vector<MaterialDescription> materials;
  std::vector<ShapeDescription> shapes;
  std::optional<SensorSettings> sensor;  // none: the film records CIE XYZ only
  IspSettings isp;                       // raw → picture (scenes with a sensor)
};

}  // namespace camsim
