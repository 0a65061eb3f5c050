// Scene: the renderable objects built from a SceneDescription — camera, shapes on Embree,
// materials, lights and the light-selection distribution (∝ power) — and the analysis of
// which dimensions of the measurement integral the scene needs (ModelledDimensions).
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "integrator/camera/physical_camera.h"
#include "integrator/geometry/embree_scene.h"
#include "integrator/lights/area_light.h"
#include "integrator/materials/material.h"
#include "integrator/sampling/distribution.h"
#include "integrator/scene/scene_description.h"
#include "integrator/scene/scene_ids.h"
#include "integrator/textures/texture.h"

namespace camsim {

// What the renderer integrates over, beyond pixel area: only what can change the image.
struct ModelledDimensions {
  bool aperture = false;   // lens positions (thin or traced lens); false: pinhole
  std::string tracedLens;  // the traced lens's file name (camera.lens); empty: thin lens
  int lensSurfaces = 0;    // its surfaces, the stop included
  bool lensDisperses = false;
  int blades = 0;            // 0: circular stop
  bool diffraction = false;  // the stop's PSF (aperture.diffraction): film-point jitter
  bool time = false;         // shutter time: something moves during the exposure
  int movingObjects = 0;
  bool cameraMoves = false;
  bool rollingShutter = false;
  int wavelengths = kWavelengthSamples;
  // The spectral control variate (integrator/render/spectral_control_variate.h): set by the
  // render when it used it.
  bool spectralControlVariate = false;
  int timeSteps = 1;  // Embree motion time steps (largest over shapes)

  // e.g. "aperture (6 blades, diffraction), time (2 moving objects, rolling shutter), 4
  // wavelengths"; a traced lens: "traced lens dgauss.50mm.dat (11 surfaces, dispersion;
  // circular stop, diffraction), …"
  std::string describe() const;
};

// The interval ray times fall in: shutter open → close of the last row (s).
glm::dvec2 exposureWindow(const PhysicalCameraParams& camera);
inline glm::dvec2 exposureWindow(const PhysicalCamera& camera) {
  return exposureWindow(camera.params());
}
// The whole frame sequence's (description.frames; none: the one frame's): frame 0's shutter
// open → the last frame's last row closed (s). Geometry and motion are built over it once.
glm::dvec2 sequenceWindow(const SceneDescription& description);

class Scene {
 public:
  explicit Scene(const SceneDescription& description);
  // For a sequence: geometry and motion built once over [span.x, span.y] (s), the whole
  // sequence's exposure; setCamera() then moves to each frame's camera and shutter.
  Scene(const SceneDescription& description, glm::dvec2 motionSpan);
  // The camera of another frame (its shutter inside the motion span): the exposure window
  // and what is modelled (time, moving objects, rolling shutter) follow it.
  void setCamera(const PhysicalCameraParams& camera);
  // The camera of another capture of `description` (the one this Scene was built from, or
  // one canRetarget accepts) over another motion span, e.g. a bracket's stretched shutter:
  // the Scene then renders exactly as Scene(description with `camera`, motionSpan) would.
  // Only what depends on the span is built again, from description's shapes: with keyframed
  // motion the shapes, their cut-outs and area lights, the BVH, the bounds and the light
  // powers; without, only Embree's time map moves. Materials, textures, alpha textures and
  // the other lights are kept: no file is read. An InputError (a shape that reaches too far
  // over the new span) leaves the Scene unusable: it must be dropped.
  void setCamera(const PhysicalCameraParams& camera, const SceneDescription& description,
                 glm::dvec2 motionSpan);

  // Reuse for another capture (SceneCache, integrator/capture/scene_cache.h). Whether this
  // Scene renders `next` exactly as Scene(next) would, once retarget(next) has run, given
  // what the caller vouches for: `next` differs from the description this was built from
  // at most in its camera, render.spp and render.seed (and its sensor, ISP and name, which
  // a Scene does not hold) — the same shapes, materials and lights. Checked here, so that
  // a capture the rule does not cover is rebuilt: the render origin, the other render
  // settings, the frames block, the counts of shapes, materials, lights and emitters.
  bool canRetarget(const SceneDescription& next) const;
  // next's camera and render settings; the motion span becomes next's exposure window, as
  // Scene(next) builds it (setCamera above: keyframed motion is built again over it).
  // CAMSIM_CHECK: canRetarget(next).
  void retarget(const SceneDescription& next);

  const PhysicalCamera& camera() const { return *camera_; }
  const RenderSettings& settings() const { return settings_; }
  // World position of render space's origin (SceneDescription::renderOrigin), m.
  const glm::dvec3& renderOrigin() const { return renderOrigin_; }
  const ModelledDimensions& modelled() const { return modelled_; }
  // The interval ray times fall in: shutter open → close of the last row.
  double exposureStart() const { return exposureStart_; }
  double exposureEnd() const { return exposureEnd_; }
  const EmbreeScene& geometry() const { return *geometry_; }
  // With the amodal aov: a crossings scene (embree_scene.h) of the labelled shapes (those
  // with a `class:`), for the amodal masks; else null.
  const EmbreeScene* labelledGeometry() const { return labelledGeometry_.get(); }
  const Shape& shape(int index) const { return *shapes_[static_cast<size_t>(index)]; }
  std::size_t shapeCount() const { return shapes_.size(); }
  // A shape's keyframed motion, object → render space (empty: static). For a mesh instance
  // the motion's object space is the placed mesh's (placement · the mesh's own space).
  const RigidMotion& motion(int shape) const { return motions_[static_cast<size_t>(shape)]; }
  // The ids of what rays hit, for the ID mattes (scene_ids.h).
  const SceneIds& ids() const { return ids_; }
  // Time from one frame's reference time to the next (s): 1 / frames.rate_hz; 0 without
  // a frames block.
  double frameInterval() const { return frameInterval_; }
  // Never null: shapes without a reflecting material get a black one.
  const Material& material(int shape) const {
    return *materials_[materialOfShape_[static_cast<size_t>(shape)]];
  }
  // The shading context at a hit on `hit.shape` whose interaction is si: its texture
  // coordinates and, on a mesh with vertex colours, the colours and where the hit lies on
  // which triangle (BsdfContext). One per shading point (its texture memo).
  BsdfContext bsdfContext(const Hit& hit, const SurfaceInteraction& si) const {
    if (colorsOfShape_.empty()) [[likely]]
      return BsdfContext(si.uv);
    const VertexColors* colors = colorsOfShape_[static_cast<size_t>(hit.shape)];
    return colors ? BsdfContext(si.uv, colors, hit.prim, hit.u, hit.v) : BsdfContext(si.uv);
  }
  // The area light of a shape, or null if it does not emit.
  const AreaLight* areaLight(int shape) const { return lightOfShape_[static_cast<size_t>(shape)]; }

  size_t lightCount() const { return lights_.size(); }
  // Whether next-event estimation has a light to pick: some light has power > 0. A scene
  // whose lights are all dark (luminance 0, scale 0, a zero spectrum) renders black
  // without light samples; emitters hit by BSDF sampling then emit nothing either.
  bool hasPoweredLights() const { return lightDistribution_.total() > 0.0; }
  // Indices of the lights that rays escaping the scene see (sun, environment).
  const std::vector<size_t>& infiniteLights() const { return infiniteLights_; }
  // Bounding sphere of the geometry at rest (m).
  glm::vec3 boundsCentre() const { return boundsCentre_; }
  float boundsRadius() const { return boundsRadius_; }
  const Light& light(size_t i) const { return *lights_[i]; }
  const DiscreteDistribution& lightDistribution() const { return lightDistribution_; }
  // The spectral control variate's reference emission E (W·m⁻²·sr⁻¹·nm⁻¹: the most
  // powerful emitting shape's radiance), or null: off (render.spectral_control_variate
  // false, or no emitting shape). integrator/render/spectral_control_variate.h.
  const Spectrum* spectralReference() const {
    return spectralReference_ ? &*spectralReference_ : nullptr;
  }
  // Probability that NEE picks the light of an emitting shape.
  float lightPmfOfShape(int shape) const {
    return lightDistribution_.pmf(lightIndexOfShape_[static_cast<size_t>(shape)]);
  }

 private:
  void analyseExposure();  // exposure window and modelled_ from camera_ and motions_
  // Everything that depends on the motion span, from d's shapes over motionSpan_ (dropping
  // what an earlier build made): shapes, motions, cut-outs, vertex colours, area lights
  // (first in lights_), the BVH and the bounds.
  void buildShapes(const SceneDescription& d);
  // The other lights' scene bounds, the infinite lights and the light distribution (∝ power).
  void weighLights();
  // The vertex colours of mesh shape s (null: none), made once per MeshData (`made`).
  const VertexColors* vertexColorsOf(const SceneDescription& d, const ShapeDescription& s,
                                     std::map<const MeshData*, const VertexColors*>& made);

  std::unique_ptr<PhysicalCamera> camera_;
  std::vector<RigidMotion> motions_;  // of each shape (empty: static)
  glm::dvec2 motionSpan_{0.0};
  RenderSettings settings_;
  glm::dvec3 renderOrigin_{0.0};
  SceneIds ids_;
  double frameInterval_ = 0.0;
  ModelledDimensions modelled_;
  double exposureStart_ = 0.0, exposureEnd_ = 0.0;
  std::vector<std::unique_ptr<Shape>> shapes_;
  std::vector<std::unique_ptr<Material>> materials_;
  std::vector<size_t> materialOfShape_;
  // Vertex colours of each shape (null: none), shared by the instances of one mesh; empty
  // when no shape has any.
  std::vector<std::unique_ptr<const VertexColors>> vertexColors_;
  std::vector<const VertexColors*> colorsOfShape_;
  std::vector<std::unique_ptr<Light>> lights_;
  std::vector<size_t> infiniteLights_;
  glm::vec3 boundsCentre_{0.0f};
  float boundsRadius_ = 0.0f;
  std::vector<const AreaLight*> lightOfShape_;
  std::vector<size_t> lightIndexOfShape_;
  DiscreteDistribution lightDistribution_;
  std::optional<Spectrum> spectralReference_;
  std::vector<std::unique_ptr<HitFilter>> filters_;  // alpha cut-outs; geometry_ points to them
  // Each cut-out material's alpha texture (null: opaque everywhere), made at its first use
  // and kept when buildShapes runs again, so that its file is read once.
  std::map<int, std::shared_ptr<const FloatTexture>> alphaOfMaterial_;
  std::size_t areaLights_ = 0;  // lights_[0, areaLights_) are the emitting shapes'
  std::unique_ptr<EmbreeScene> geometry_;
  std::unique_ptr<EmbreeScene> labelledGeometry_;  // with the amodal aov (labelledGeometry())
};

}  // namespace camsim
