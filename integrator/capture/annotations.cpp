#include "integrator/capture/annotations.h"

#include <algorithm>
#include <array>
#include <limits>

#include "integrator/camera/physical_camera.h"
#include "integrator/scene/scene_ids.h"

namespace camsim {
namespace {

// The shape's bounds in its own space (render space for a static shape): min, max.
std::array<glm::dvec3, 2> objectBounds(const ShapeDescription& s) {
  if (s.kind == ShapeDescription::Kind::kSphere) {
    const glm::dvec3 c(s.centre), r(static_cast<double>(s.radius));
    return {c - r, c + r};
  }
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::vec3& p : s.mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  return {lo, hi};
}

// The 2-D box of the shape's projected world-axis box at time t (corner convention).
std::optional<glm::dvec4> projectedBox(const ShapeDescription& s, const PhysicalCamera& camera,
                                       double t) {
  const std::array<glm::dvec3, 2> b = objectBounds(s);
  const glm::dmat4 m = s.motion.empty() ? glm::dmat4(1.0) : s.motion.at(t);
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p(b[c & 1].x, b[(c >> 1) & 1].y, b[(c >> 2) & 1].z);
    const glm::dvec3 w(m * glm::dvec4(p, 1.0));
    lo = glm::min(lo, w);
    hi = glm::max(hi, w);
  }
  glm::dvec2 plo(std::numeric_limits<double>::max()), phi(-std::numeric_limits<double>::max());
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 w((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const std::optional<glm::dvec2> q = camera.project(w, t);
    if (!q) return std::nullopt;
    plo = glm::min(plo, *q + 0.5);
    phi = glm::max(phi, *q + 0.5);
  }
  return glm::dvec4(plo, phi - plo);
}

}  // namespace

std::vector<InstanceAnnotation> annotateFrame(const CaptureResult& r) {
  const Image& a = r.aovs;
  const int channel = a.channelIndex("instance.id");
  if (channel < 0) return {};
  const SceneDescription& d = r.description;
  const SceneIds ids = sceneIds(d);
  const IdTable& classes = ids[IdKind::kClass];
  const PhysicalCamera camera(d.camera);
  const double t = d.camera.shutter.centre();
  std::vector<InstanceAnnotation> out;
  for (std::size_t s = 0; s < d.shapes.size(); ++s) {
    const std::uint32_t cls = classes.ofShape[s];
    if (cls == 0) continue;
    const auto number = static_cast<float>(s + 1);  // the instance's dominant-id value
    InstanceAnnotation ann;
    int x0 = a.width, y0 = a.height, x1 = -1, y1 = -1;
    bool inside = false;
    std::uint64_t run = 0;
    for (int x = 0; x < a.width; ++x)
      for (int y = 0; y < a.height; ++y) {
        const bool on = a.at(x, y, channel) == number;
        if (on != inside) {
          ann.rle.push_back(run);
          run = 0;
          inside = on;
        }
        ++run;
        if (!on) continue;
        ++ann.area;
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
      }
    if (ann.area == 0) continue;
    ann.rle.push_back(run);
    ann.instance = static_cast<std::uint32_t>(s + 1);
    ann.name = d.shapes[s].label;
    ann.category = classes.numbers[cls];
    ann.categoryName = classes.names[cls];
    ann.bbox = {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
    ann.bbox3d = projectedBox(d.shapes[s], camera, t);
    out.push_back(std::move(ann));
  }
  return out;
}

}  // namespace camsim
