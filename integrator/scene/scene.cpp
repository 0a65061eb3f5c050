#include "integrator/scene/scene.h"

#include <algorithm>
#include <cmath>

#include "integrator/geometry/sphere.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/materials/diffuse_material.h"
#include "integrator/scene/factory.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

// Time steps for a moving shape: linear interpolation between steps must follow the
// keyframed rotation closely (≤ 2° per step: chord error < 1.6e-4 of the radius) and
// must not skip keyframes (≥ 4 steps per key interval inside the span). At most 129, Embree's
// RTC_MAX_TIME_STEP_COUNT (more fails in rtcSetGeometryTimeStepCount).
int timeStepsFor(const RigidMotion& motion, double t0, double t1) {
  const double degrees = motion.rotationAngleDuring(t0, t1) * 180.0 / M_PI;
  int keysInside = 0;
  for (const Keyframe& k : motion.keys()) keysInside += (k.time > t0 && k.time < t1) ? 1 : 0;
  const int steps = 1 + std::max(static_cast<int>(std::ceil(degrees / 2.0)), 4 * (keysInside + 1));
  return std::clamp(steps, 2, 129);
}

std::unique_ptr<Shape> buildShape(const ShapeDescription& s, double t0, double t1, bool& moving) {
  moving = !s.motion.empty() && !s.motion.isStaticDuring(t0, t1);
  TimeSteps steps{t0, t1, moving ? timeStepsFor(s.motion, t0, t1) : 1};
  auto transformAt = [&](int k) {
    return s.motion.empty() ? glm::dmat4(1.0) : s.motion.at(steps.timeOf(k));
  };
  if (s.kind == ShapeDescription::Kind::kSphere) {
    std::vector<glm::vec3> centres;
    std::vector<float> radii;
    for (int k = 0; k < steps.count; ++k) {
      const glm::dmat4 m = transformAt(k);
      centres.emplace_back(m * glm::dvec4(glm::dvec3(s.centre), 1.0));
      radii.push_back(
          static_cast<float>(glm::length(glm::dvec3(m[0])) * static_cast<double>(s.radius)));
    }
    return std::make_unique<Sphere>(std::move(centres), std::move(radii), steps);
  }
  // A mesh stores one pose: the reference of its instance motion (Shape), or its only one.
  std::vector<glm::dmat4> poses;
  for (int k = 0; k < steps.count; ++k) poses.push_back(transformAt(k));
  InstanceMotion instance = InstanceMotion::fromPoses(poses);
  const glm::dmat4& m = poses[static_cast<size_t>(instance.reference)];
  std::vector<glm::vec3> positions;
  positions.reserve(s.mesh.positions.size() + TriangleMesh::kSpareVertices);
  for (const glm::vec3& v : s.mesh.positions)
    positions.emplace_back(m * glm::dvec4(glm::dvec3(v), 1.0));
  std::vector<glm::vec3> normals;
  const glm::dmat3 rotation(m);  // uniform scale: normals only need renormalising
  for (const glm::vec3& n : s.mesh.normals)
    normals.emplace_back(glm::normalize(rotation * glm::dvec3(n)));
  std::vector<glm::vec4> tangents;  // turned like the normals; w (the handedness) kept
  for (const glm::vec4& t : s.mesh.tangents) {
    const glm::dvec3 turned = rotation * glm::dvec3(t);
    const double len = glm::length(turned);
    tangents.emplace_back(glm::vec3(len > 0.0 ? turned / len : turned), t.w);
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(s.mesh.indices.size() + TriangleMesh::kSpareIndices);
  indices.assign(s.mesh.indices.begin(), s.mesh.indices.end());
  return std::make_unique<TriangleMesh>(
      std::move(positions), std::move(normals), std::move(indices), steps, s.mesh.uvs,
      s.emission.has_value(), std::move(instance), std::move(tangents));
}

}  // namespace

std::string ModelledDimensions::describe() const {
  std::string out;
  if (aperture)
    out +=
        blades > 0 ? "aperture (" + std::to_string(blades) + " blades), " : "aperture (circular), ";
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
  return out + std::to_string(wavelengths) + " wavelengths";
}

glm::dvec2 exposureWindow(const PhysicalCamera& camera) {
  const Shutter& shutter = camera.shutter();
  return {shutter.open(), shutter.close() + shutter.rowOffset(camera.resolution().y - 1)};
}

Scene::Scene(const SceneDescription& d) : Scene(d, exposureWindow(PhysicalCamera(d.camera))) {}

void Scene::setCamera(const PhysicalCameraParams& camera) {
  camera_ = std::make_unique<PhysicalCamera>(camera);
  const glm::dvec2 w = exposureWindow(*camera_);
  CAMSIM_CHECK(w.x >= motionSpan_.x && w.y <= motionSpan_.y);
  analyseExposure();
}

bool Scene::canRetarget(const SceneDescription& next) const {
  const RenderSettings& a = settings_;
  const RenderSettings& b = next.render;
  if (a.sampler != b.sampler || a.maxDepth != b.maxDepth || a.rrDepth != b.rrDepth ||
      a.aovs != b.aovs)
    return false;
  if (next.renderOrigin != renderOrigin_ ||
      (next.frames ? 1.0 / next.frames->rateHz : 0.0) != frameInterval_)
    return false;
  std::size_t emitters = 0;
  for (const ShapeDescription& shape : next.shapes) emitters += shape.emission ? 1 : 0;
  if (next.shapes.size() != shapes_.size() || next.materials.size() + 1 != materials_.size() ||
      next.lights.size() + emitters != lights_.size())
    return false;
  const glm::dvec2 w = exposureWindow(PhysicalCamera(next.camera));
  if (w == motionSpan_) return true;
  return std::all_of(motions_.begin(), motions_.end(),
                     [](const RigidMotion& m) { return m.empty(); });
}

void Scene::retarget(const SceneDescription& next) {
  CAMSIM_CHECK(canRetarget(next));
  camera_ = std::make_unique<PhysicalCamera>(next.camera);
  if (const glm::dvec2 w = exposureWindow(*camera_); w != motionSpan_) {
    motionSpan_ = w;  // nothing has keyframed motion (canRetarget): only Embree's time map moves
    geometry_->setMotionSpan(w.x, w.y);
  }
  settings_ = next.render;
  analyseExposure();
}

void Scene::analyseExposure() {
  const glm::dvec2 w = exposureWindow(*camera_);
  exposureStart_ = w.x;
  exposureEnd_ = w.y;
  modelled_.aperture = camera_->hasAperture();
  modelled_.blades = camera_->params().aperture ? camera_->params().aperture->blades : 0;
  modelled_.cameraMoves = camera_->moves(exposureStart_, exposureEnd_);
  modelled_.movingObjects = 0;
  for (const RigidMotion& m : motions_)
    modelled_.movingObjects += !m.empty() && !m.isStaticDuring(exposureStart_, exposureEnd_);
  modelled_.time = modelled_.cameraMoves || modelled_.movingObjects > 0;
  modelled_.rollingShutter = modelled_.time && camera_->shutter().type() == Shutter::Type::kRolling;
}

Scene::Scene(const SceneDescription& d, glm::dvec2 motionSpan)
    : motionSpan_(motionSpan),
      settings_(d.render),
      renderOrigin_(d.renderOrigin),
      ids_(sceneIds(d)),
      frameInterval_(d.frames ? 1.0 / d.frames->rateHz : 0.0) {
  camera_ = std::make_unique<PhysicalCamera>(d.camera);
  exposureStart_ = motionSpan.x;  // the shapes' motion is built over the whole span
  exposureEnd_ = motionSpan.y;

  materials_.push_back(std::make_unique<DiffuseMaterial>(Spectrum::constant(0.0)));  // black
  TextureCache textures;  // a texture named by several materials is uplifted once
  for (const MaterialDescription& m : d.materials) materials_.push_back(makeMaterial(m, &textures));

  std::vector<double> powers;
  for (const ShapeDescription& s : d.shapes) {
    bool moving = false;
    shapes_.push_back(buildShape(s, exposureStart_, exposureEnd_, moving));
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
      lightIndexOfShape_.back() = lights_.size();
      powers.push_back(light->power());
      lights_.push_back(std::move(light));
    }
  }
  geometry_ = std::make_unique<EmbreeScene>(shapes_, exposureStart_, exposureEnd_);
  if (geometry_->boundsLower().x <= geometry_->boundsUpper().x) {
    boundsCentre_ = 0.5f * (geometry_->boundsLower() + geometry_->boundsUpper());
    boundsRadius_ = 0.5f * glm::length(geometry_->boundsUpper() - geometry_->boundsLower());
  }
  for (const LightDescription& l : d.lights) {
    lights_.push_back(makeLight(l));
    if (lights_.back()->isInfinite()) infiniteLights_.push_back(lights_.size() - 1);
  }
  for (size_t i = powers.size(); i < lights_.size(); ++i) {
    lights_[i]->setSceneBounds(boundsCentre_, boundsRadius_);
    powers.push_back(lights_[i]->power());
  }
  if (!powers.empty()) lightDistribution_ = DiscreteDistribution(powers);
  analyseExposure();
}

}  // namespace camsim
