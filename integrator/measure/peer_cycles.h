// `camsim bench --peer cycles`: a camsim scene as a Blender Python script that renders it
// with Cycles (Debian's blender, 3.4) at settings matched to camsim's.
//
// | camsim                                  | Cycles                                               |
// |-----------------------------------------|------------------------------------------------------|
// | shapes (meshes; spheres)                | meshes in render space (m); spheres as UV spheres of  |
// |                                         | kSphereSegments × kSphereRings quads, smooth-shaded  |
// | diffuse ρ(λ)                            | Diffuse BSDF, colour = ρ's linear Rec.709 RGB under   |
// |                                         | D65 (reflectanceToRgb)                               |
// | mirror ρ(λ)                             | Glossy BSDF, sharp, colour as above                  |
// | emission L_e(λ), one-sided              | Emission, colour = XYZ(L_e) → linear Rec.709 (absolute|
// |                                         | up to one common factor), strength 0 on back faces   |
// | pinhole / thin lens f, N, s, blades     | lens = image distance z_i = f s/(s − f) (same field   |
// |                                         | of view), f-stop z_i/(f/N) (same pupil), focus s      |
// | max_depth D (scattering events)         | max_bounces D − 1 (every kind; Cycles counts bounces |
// |                                         | after the first hit)                                 |
// Cycles settings: CPU, fixed thread count, no denoiser, no adaptive sampling, no light
// clamping, no glossy filter, caustics on, no persistent data (with it, Blender 3.4 keeps
// the first render's samples and seed for the later ones), its default pixel filter (Blackman-Harris, 1.5 px), Standard view, 32-bit float EXR (R,
// G, B linear Rec.709). Each render is timed in the script around bpy.ops.render.render
// (Blender's start-up, the scene's set-up in Python and the EXR's writing excluded; Cycles'
// sync and BVH build included, milliseconds for the bench scenes) and printed as
// "camsim-peer: INDEX SECONDS"; a 1-spp warm-up render comes first.
//
// Not translated (InputError naming the feature): textures other than constants, other
// material types (conductor, dielectric, plastic, metallic_roughness), lights that are not
// shapes (point, spot, distant, environment), motion during the shutter, a sensor model.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "integrator/scene/scene_description.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

inline constexpr int kSphereSegments = 96, kSphereRings = 48;

struct CyclesRender {
  int spp = 1;
  std::uint64_t seed = 0;
  std::string file;  // EXR written
};

struct CyclesSettings {
  int threads = 1;
  int bounces = 15;                   // Cycles max_bounces (camsim max_depth − 1)
  std::string warmupFile;             // empty: no warm-up render
  std::vector<CyclesRender> renders;  // in order
};

struct CyclesTranslation {
  std::string script;  // Python for `blender -b --factory-startup --python`
  // The features approximated, one sentence each (spectral → RGB, spheres tessellated, ...).
  std::vector<std::string> approximations;
};

// InputError (the scene file, the shape or material, the feature) if the scene uses what
// the translation does not cover.
CyclesTranslation translateToCycles(const SceneDescription& scene, const CyclesSettings& settings);

// Linear Rec.709 RGB of a reflectance under D65 (the Rec.709 white).
glm::dvec3 cyclesReflectanceRgb(const Spectrum& reflectance);
// Linear Rec.709 RGB of a spectral radiance: XYZ = Σ L cmf (W·m⁻²·sr⁻¹ × cmf), no 683.
glm::dvec3 cyclesRadianceRgb(const Spectrum& radiance);

// A Python string literal of s (double quotes; backslash, quote and control characters
// escaped).
std::string pythonString(const std::string& s);

}  // namespace camsim
