#include "integrator/render/occlusion_film.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "integrator/geometry/mesh_instance.h"
#include "integrator/geometry/sphere.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/scene/scene.h"

namespace camsim {
namespace {

double spanEnd(const std::array<double, 3>& times) {
  return times[2] > times[0] ? times[2] : times[0] + 1.0;
}

// A keyframed shape copied into a BVH of its own with two time steps, its poses at
// times[0] and times[2] (the ends of the span: Embree's time 0 and 1, no interpolation).
// The scene's shape stores its pose at one time t_ref of its own motion span; the copy
// takes it through Y_j = M(t_j) · M(t_ref)⁻¹ (M: the shape's keyframed motion, object →
// render space), the same exact motion the motion field moves hit points with.
std::unique_ptr<Shape> movedCopy(const Shape& shape, const RigidMotion& motion,
                                 const std::array<double, 3>& times) {
  // Without a frame interval (no frames block) the three times coincide: both steps then
  // hold the one pose, over a span of 1 s.
  const TimeSteps span{times[0], spanEnd(times), 2};
  const auto toTimes = [&](int step) {
    const glm::dmat4 inverse = glm::inverse(motion.at(shape.timeSteps().timeOf(step)));
    return std::array<glm::dmat4, 2>{motion.at(times[0]) * inverse, motion.at(times[2]) * inverse};
  };
  if (const auto* sphere = dynamic_cast<const Sphere*>(&shape)) {  // step 0's centre, radius
    const std::array<glm::dmat4, 2> y = toTimes(0);
    const glm::dvec4 c(glm::dvec3(sphere->centres()[0]), 1.0);
    const double r = static_cast<double>(sphere->radii()[0]);
    return std::make_unique<Sphere>(
        std::vector<glm::vec3>{glm::vec3(y[0] * c), glm::vec3(y[1] * c)},
        std::vector<float>{static_cast<float>(r * glm::length(glm::dvec3(y[0][0]))),
                           static_cast<float>(r * glm::length(glm::dvec3(y[1][0])))},
        span);
  }
  if (const auto* instance = dynamic_cast<const MeshInstance*>(&shape)) {  // step 0's placement
    const std::array<glm::dmat4, 2> y = toTimes(0);
    const glm::dmat4 placement(instance->placement());
    return std::make_unique<MeshInstance>(
        instance->mesh(), std::vector<glm::dmat4>{y[0] * placement, y[1] * placement}, span, false);
  }
  const auto& mesh = dynamic_cast<const TriangleMesh&>(shape);  // the stored (reference) pose
  const InstanceMotion& own = mesh.instanceMotion();
  const std::array<glm::dmat4, 2> y = toTimes(own.empty() ? 0 : own.reference);
  InstanceMotion moved;
  for (const glm::dmat4& m : y) {
    moved.steps.emplace_back(m);
    for (int i = 0; i < 3; ++i)
      moved.translation = std::max(moved.translation, static_cast<float>(std::abs(m[3][i])));
  }
  return std::make_unique<TriangleMesh>(mesh.positions(), std::vector<glm::vec3>{}, mesh.indices(),
                                        span, std::vector<glm::vec2>{}, false, std::move(moved));
}

}  // namespace

OcclusionFilm::OcclusionFilm(const Scene& scene, const std::array<double, 3>& times,
                             const std::array<glm::dmat4, 3>& worldFromCamera)
    : scene_(scene), times_(times), worldFromCamera_(worldFromCamera) {
  imageEnd_ = glm::dvec2(scene.camera().resolution()) - 0.5;
  keyframed_.assign(scene.shapeCount(), 0);
  for (std::size_t s = 0; s < scene.shapeCount(); ++s) {
    const RigidMotion& motion = scene.motion(static_cast<int>(s));
    if (motion.empty()) continue;
    keyframed_[s] = 1;
    movedShapes_.push_back(movedCopy(scene.shape(static_cast<int>(s)), motion, times));
  }
  anyKeyframed_ = !movedShapes_.empty();
  if (anyKeyframed_) moved_ = std::make_unique<EmbreeScene>(movedShapes_, times[0], spanEnd(times));
}

OcclusionFilm::~OcclusionFilm() = default;

bool OcclusionFilm::hidden(const Ray& ray) const {
  if (moved_ && moved_->occluded(ray)) return true;
  // The scene's BVH holds the keyframed shapes where they are during this frame's exposure:
  // their hits are rejected by the query's filter (one traversal), their copies in moved_
  // stand for them.
  return scene_.geometry().occluded(
      ray, anyKeyframed_ ? std::span<const char>(keyframed_) : std::span<const char>());
}

OcclusionFilm::Seen OcclusionFilm::classify(const glm::dvec3& x, std::size_t j) const {
  const glm::dmat4& pose = worldFromCamera_[j];
  const std::optional<glm::dvec2> q = scene_.camera().projectFrom(pose, x);
  if (!q || !(q->x >= -0.5 && q->x < imageEnd_.x && q->y >= -0.5 && q->y < imageEnd_.y))
    return Seen::kOutside;
  // The segment from the projection centre to the point, short of it by ε of its length.
  const glm::dvec3 o(pose[3]);
  Ray ray;
  ray.o = glm::vec3(o);
  ray.d = glm::vec3(x - o);
  ray.tMax = static_cast<float>(1.0 - kEndGap);
  ray.time = times_[j];
  return hidden(ray) ? Seen::kOccluded : Seen::kVisible;
}

void OcclusionFilm::add(const PosePoints& p, int lanes, OcclusionSums& sums) const {
  for (int lane = 0; lane < lanes; ++lane) {
    ++sums.samples;
    for (std::size_t j : {std::size_t{2}, std::size_t{0}}) {  // forward, then backward
      const std::size_t backward = j == 0 ? 1 : 0;
      const Seen seen = classify(glm::dvec3(p.x[j][lane], p.y[j][lane], p.z[j][lane]), j);
      if (seen == Seen::kOccluded) ++sums.counts[backward];
      if (seen == Seen::kOutside) ++sums.counts[2 + backward];
    }
  }
}

void OcclusionFilm::write(const OcclusionSums& sums, float* o) {
  if (sums.samples == 0) return;
  for (std::size_t c = 0; c < sums.counts.size(); ++c)
    o[c] = static_cast<float>(static_cast<double>(sums.counts[c]) / sums.samples);
}

}  // namespace camsim
