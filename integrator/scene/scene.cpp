#include "integrator/scene/scene.h"

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <iterator>
#include <map>
#include <utility>

#include "integrator/materials/diffuse_material.h"
#include "integrator/scene/factory.h"
#include "integrator/scene/scene_shapes.h"
#include "sensor/base/check.h"
#include "sensor/base/input_error.h"

namespace camsim {

std::string ModelledDimensions::describe() const {
  std::string out;
  const std::string stop = (blades > 0 ? std::to_string(blades) + "-blade" : "circular") +
                           std::string(" stop") + (diffraction ? ", diffraction" : "");
  if (!tracedLens.empty())
    out += "traced lens " + tracedLens + " (" + std::to_string(lensSurfaces) + " surfaces" +
           (lensDisperses ? ", dispersion; " : "; ") + stop + "), ";
  else if (aperture)
    out += "aperture (" + (blades > 0 ? std::to_string(blades) + " blades" : "circular") +
           (diffraction ? ", diffraction), " : "), ");
  else
    out += "pinhole, ";
  if (time) {
    std::string why;
    if (movingObjects > 0)
      why += std::to_string(movingObjects) +
             (movingObjects == 1 ? " moving object" : " moving objects");
    if (cameraMoves) why += std::string(why.empty() ? "" : ", ") + "moving camera";
    if (rollingShutter) why += ", rolling shutter";
    out += "time (" + why + "; " + std::to_string(timeSteps) + " motion steps), ";
  } else {
    out += "static (no time sampling), ";
  }
  return out + std::to_string(wavelengths) + " wavelengths" +
         (spectralControlVariate ? " with the spectral control variate" : "");
}

// From the parameters alone: a camera need not be made (a traced lens's would build its
// pupil bounds, ≈ 0.1 s, only to read the shutter).
glm::dvec2 exposureWindow(const PhysicalCameraParams& camera) {
  const Shutter& shutter = camera.shutter;
  return {shutter.open(), shutter.close() + shutter.rowOffset(camera.resolution.y - 1)};
}

glm::dvec2 sequenceWindow(const SceneDescription& d) {
  const int count = d.frames ? d.frames->count : 1;
  return {exposureWindow(d.frameCamera(0)).x, exposureWindow(d.frameCamera(count - 1)).y};
}

Scene::Scene(const SceneDescription& d) : Scene(d, exposureWindow(d.camera)) {}

void Scene::setCamera(const PhysicalCameraParams& camera) {
  camera_ = std::make_unique<PhysicalCamera>(camera);
  const glm::dvec2 w = exposureWindow(*camera_);
  CAMSIM_CHECK(w.x >= motionSpan_.x && w.y <= motionSpan_.y);
  analyseExposure();
}

void Scene::setCamera(const PhysicalCameraParams& camera, const SceneDescription& d,
                      glm::dvec2 motionSpan) {
  if (motionSpan != motionSpan_) {
    motionSpan_ = motionSpan;
    const bool keyframed = std::any_of(d.shapes.begin(), d.shapes.end(),
                                       [](const ShapeDescription& s) { return !s.motion.empty(); });
    if (keyframed) {
      buildShapes(d);  // materials, textures and the other lights are kept: no file is read
      weighLights();   // the bounds (sun, environment) and the area lights' powers
    } else {
      geometry_->setMotionSpan(motionSpan.x, motionSpan.y);  // only Embree's time map moves
      if (labelledGeometry_) labelledGeometry_->setMotionSpan(motionSpan.x, motionSpan.y);
    }
  }
  setCamera(camera);
}

bool Scene::canRetarget(const SceneDescription& next) const {
  const RenderSettings& a = settings_;
  const RenderSettings& b = next.render;
  if (a.sampler != b.sampler || a.maxDepth != b.maxDepth || a.rrDepth != b.rrDepth ||
      a.aovs != b.aovs || a.spectralControlVariate != b.spectralControlVariate)
    return false;
  if (next.renderOrigin != renderOrigin_ ||
      (next.frames ? 1.0 / next.frames->rateHz : 0.0) != frameInterval_)
    return false;
  std::size_t emitters = 0;
  for (const ShapeDescription& shape : next.shapes) emitters += shape.emission ? 1 : 0;
  return next.shapes.size() == shapes_.size() && next.materials.size() + 1 == materials_.size() &&
         next.lights.size() + emitters == lights_.size() && emitters == areaLights_;
}

void Scene::retarget(const SceneDescription& next) {
  CAMSIM_CHECK(canRetarget(next));
  settings_ = next.render;
  const PhysicalCameraParams& camera = next.camera;
  setCamera(camera, next, exposureWindow(camera));
}

void Scene::analyseExposure() {
  const glm::dvec2 w = exposureWindow(*camera_);
  exposureStart_ = w.x;
  exposureEnd_ = w.y;
  modelled_.aperture = camera_->hasAperture();
  const PhysicalCameraParams& params = camera_->params();
  modelled_.blades = params.lens       ? params.lens->blades
                     : params.aperture ? params.aperture->blades
                                       : 0;
  modelled_.diffraction = camera_->diffraction() != nullptr;
  const LensCamera* lens = camera_->lensCamera();
  modelled_.tracedLens =
      lens ? std::filesystem::path(lens->lens().prescription().source).filename().string()
           : std::string();
  modelled_.lensSurfaces = lens ? lens->lens().surfaceCount() : 0;
  modelled_.lensDisperses = lens && lens->disperses();
  modelled_.cameraMoves = camera_->moves(exposureStart_, exposureEnd_);
  modelled_.movingObjects = 0;
  for (const RigidMotion& m : motions_)
    modelled_.movingObjects += !m.empty() && !m.isStaticDuring(exposureStart_, exposureEnd_);
  modelled_.time = modelled_.cameraMoves || modelled_.movingObjects > 0;
  modelled_.rollingShutter = modelled_.time && camera_->shutter().type() == Shutter::Type::kRolling;
}

const VertexColors* Scene::vertexColorsOf(const SceneDescription& d, const ShapeDescription& s,
                                          std::map<const MeshData*, const VertexColors*>& made) {
  const MeshData& mesh = s.sharedMesh ? *s.sharedMesh : s.mesh;
  if (mesh.colors.empty()) return nullptr;
  if (mesh.colors.size() != mesh.positions.size())
    throw shapeError(d, s,
                     "the mesh has " + std::to_string(mesh.colors.size()) + " vertex colours for " +
                         std::to_string(mesh.positions.size()) + " vertices");
  const VertexColors*& colors = made[&mesh];
  if (!colors) {
    vertexColors_.push_back(std::make_unique<const VertexColors>(mesh.colors, mesh.indices));
    colors = vertexColors_.back().get();
  }
  return colors;
}

Scene::Scene(const SceneDescription& d, glm::dvec2 motionSpan)
    : motionSpan_(motionSpan),
      settings_(d.render),
      renderOrigin_(d.renderOrigin),
      ids_(sceneIds(d)),
      frameInterval_(d.frames ? 1.0 / d.frames->rateHz : 0.0) {
  try {
    camera_ = std::make_unique<PhysicalCamera>(d.camera);
  } catch (const InputError& e) {  // found building the camera (a lens passing no light)
    throw inFile(e, d.sourceFile);
  }
  materials_.push_back(std::make_unique<DiffuseMaterial>(Spectrum::constant(0.0)));  // black
  TextureCache textures;  // a texture named by several materials is uplifted once
  for (const MaterialDescription& m : d.materials) materials_.push_back(makeMaterial(m, &textures));
  buildShapes(d);
  for (const LightDescription& l : d.lights) lights_.push_back(makeLight(l));
  weighLights();
  analyseExposure();
}

void Scene::buildShapes(const SceneDescription& d) {
  // What points at the shapes goes first: the BVHs, the area lights, the cut-outs.
  geometry_.reset();
  labelledGeometry_.reset();
  lights_.erase(lights_.begin(), lights_.begin() + static_cast<std::ptrdiff_t>(areaLights_));
  areaLights_ = 0;
  filters_.clear();
  shapes_.clear();
  motions_.clear();
  materialOfShape_.clear();
  lightOfShape_.clear();
  lightIndexOfShape_.clear();
  vertexColors_.clear();
  colorsOfShape_.clear();
  modelled_.timeSteps = 1;
  boundsCentre_ = glm::vec3(0.0f);
  boundsRadius_ = 0.0f;

  // A mesh that several shapes place is stored once and instanced; one placed once is baked
  // (a single-level BVH traces faster).
  std::map<const MeshData*, int> placements;
  for (const ShapeDescription& s : d.shapes)
    if (s.kind == ShapeDescription::Kind::kMesh && s.sharedMesh) {
      checkPlacement(d, s);
      ++placements[s.sharedMesh.get()];
    }
  std::map<const MeshData*, std::shared_ptr<const TriangleMesh>> objectMeshes;
  // One cut-out per (mesh Embree reports, material) however many instances share it.
  std::map<std::pair<const TriangleMesh*, int>, const HitFilter*> cutouts;
  std::vector<const HitFilter*> filterOfShape;
  std::vector<std::unique_ptr<Light>> areaLights;  // the shapes' lights come first in lights_
  std::map<const MeshData*, double> meshReach;
  std::map<const MeshData*, const VertexColors*> colorsOfMesh;
  std::vector<const VertexColors*> colorsOfShape;
  for (const ShapeDescription& s : d.shapes) {
    bool moving = false;
    std::shared_ptr<const TriangleMesh> instanced;
    if (s.sharedMesh && placements[s.sharedMesh.get()] > 1) {
      std::shared_ptr<const TriangleMesh>& mesh = objectMeshes[s.sharedMesh.get()];
      if (!mesh) mesh = objectMesh(*s.sharedMesh);
      instanced = mesh;
    }
    shapes_.push_back(buildShape(d, s, motionSpan_.x, motionSpan_.y, instanced, meshReach, moving));
    filterOfShape.push_back(nullptr);
    const MaterialDescription* material =
        s.material < 0 ? nullptr : &d.materials[static_cast<size_t>(s.material)];
    if (material && material->alphaCutout) {
      if (s.kind != ShapeDescription::Kind::kMesh)
        throw shapeError(d, s,
                         "material '" + material->name +
                             "' has an alpha cut-out, which needs a mesh with texture "
                             "coordinates (a sphere has none)");
      if (s.emission)
        throw shapeError(d, s,
                         "material '" + material->name +
                             "' has an alpha cut-out and the shape emits: cut-out emitters "
                             "are not supported");
      const TriangleMesh& mesh =
          instanced ? *instanced : dynamic_cast<const TriangleMesh&>(*shapes_.back());
      const HitFilter*& filter = cutouts[{&mesh, s.material}];
      if (!filter) {
        // The material's alpha texture is made once per Scene and kept across rebuilds.
        auto [alpha, added] = alphaOfMaterial_.try_emplace(s.material);
        if (added) alpha->second = makeAlphaTexture(*material->alphaCutout);
        if (alpha->second) {
          filters_.push_back(makeAlphaCutout(*material->alphaCutout, alpha->second, mesh));
          filter = filters_.back().get();
        }
      }
      filterOfShape.back() = filter;
    }
    colorsOfShape.push_back(
        s.kind == ShapeDescription::Kind::kMesh ? vertexColorsOf(d, s, colorsOfMesh) : nullptr);
    motions_.push_back(s.motion);
    if (moving)
      modelled_.timeSteps = std::max(modelled_.timeSteps, shapes_.back()->timeSteps().count);
    materialOfShape_.push_back(s.material < 0 ? 0 : static_cast<size_t>(s.material) + 1);
    lightOfShape_.push_back(nullptr);
    lightIndexOfShape_.push_back(0);
    if (s.emission) {
      auto light =
          std::make_unique<AreaLight>(*shapes_.back(), s.emission->radiance, s.emission->twoSided);
      lightOfShape_.back() = light.get();
      lightIndexOfShape_.back() = areaLights.size();
      areaLights.push_back(std::move(light));
    }
  }
  if (!vertexColors_.empty()) colorsOfShape_ = std::move(colorsOfShape);
  areaLights_ = areaLights.size();
  lights_.insert(lights_.begin(), std::make_move_iterator(areaLights.begin()),
                 std::make_move_iterator(areaLights.end()));
  geometry_ = std::make_unique<EmbreeScene>(shapes_, motionSpan_.x, motionSpan_.y, filterOfShape);
  checkInstanceRanges(d, shapes_, geometry_->boundsLower(), geometry_->boundsUpper());
  const std::vector<Aov>& aovs = settings_.aovs;
  if (std::find(aovs.begin(), aovs.end(), Aov::kAmodal) != aovs.end()) {
    std::vector<char> labelled(shapes_.size());
    for (std::size_t i = 0; i < shapes_.size(); ++i)
      labelled[i] = ids_[IdKind::kClass].ofShape[i] != 0;
    labelledGeometry_ = std::make_unique<EmbreeScene>(shapes_, motionSpan_.x, motionSpan_.y,
                                                      filterOfShape, labelled);
  }
  if (geometry_->boundsLower().x <= geometry_->boundsUpper().x) {
    boundsCentre_ = 0.5f * (geometry_->boundsLower() + geometry_->boundsUpper());
    boundsRadius_ = 0.5f * glm::length(geometry_->boundsUpper() - geometry_->boundsLower());
  }
}

void Scene::weighLights() {
  infiniteLights_.clear();
  std::vector<double> powers;
  for (size_t i = 0; i < lights_.size(); ++i) {
    if (i >= areaLights_) lights_[i]->setSceneBounds(boundsCentre_, boundsRadius_);
    if (lights_[i]->isInfinite()) infiniteLights_.push_back(i);
    powers.push_back(lights_[i]->power());
  }
  lightDistribution_ = powers.empty() ? DiscreteDistribution() : DiscreteDistribution(powers);
  // The spectral control variate's reference emission: the most powerful emitting shape's
  // (the first of equals); every area light then holds its bins against it.
  spectralReference_.reset();
  if (!settings_.spectralControlVariate) return;
  std::size_t best = areaLights_;
  for (std::size_t i = 0; i < areaLights_; ++i)
    if (powers[i] > 0.0 && (best == areaLights_ || powers[i] > powers[best])) best = i;
  if (best == areaLights_) return;
  spectralReference_ = dynamic_cast<const AreaLight&>(*lights_[best]).radiance();
  const SpectralBins referenceAverages = binAverages(*spectralReference_);
  for (std::size_t i = 0; i < areaLights_; ++i)
    dynamic_cast<AreaLight&>(*lights_[i]).setControlVariateReference(referenceAverages);
}

}  // namespace camsim
