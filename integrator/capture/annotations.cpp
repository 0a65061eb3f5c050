#include "integrator/capture/annotations.h"

#include <algorithm>
#include <array>
#include <limits>

#include "integrator/camera/physical_camera.h"
#include "integrator/scene/scene_ids.h"

namespace camsim {
namespace {

// The shape's bounds in the space its motion moves (render space for a static shape): min,
// max. An instance's are its placed vertices' (placement · object space), not the placed
// object box's corners, which a rotation would widen.
std::array<glm::dvec3, 2> objectBounds(const ShapeDescription& s) {
  if (s.kind == ShapeDescription::Kind::kSphere) {
    const glm::dvec3 c(s.centre), r(static_cast<double>(s.radius));
    return {c - r, c + r};
  }
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  if (s.sharedMesh) {
    for (const glm::vec3& p : s.sharedMesh->positions) {
      const glm::dvec3 placed(s.placement * glm::dvec4(glm::dvec3(p), 1.0));
      lo = glm::min(lo, placed);
      hi = glm::max(hi, placed);
    }
    return {lo, hi};
  }
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
  // One pass down the columns (COCO's RLE order): each pixel's dominant instance extends
  // its mask. Per instance: its annotation and its current run of 1s [runStart, end).
  struct Mask {
    InstanceAnnotation ann;
    std::uint64_t runStart = 0, end = 0;
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  };
  std::vector<Mask> masks(d.shapes.size());
  for (int x = 0; x < a.width; ++x)
    for (int y = 0; y < a.height; ++y) {
      const auto number = static_cast<std::size_t>(a.at(x, y, channel));  // shape index + 1
      if (number == 0 || classes.ofShape[number - 1] == 0) continue;      // nothing, unlabelled
      Mask& m = masks[number - 1];
      const std::uint64_t i = static_cast<std::uint64_t>(x) * static_cast<std::uint64_t>(a.height) +
                              static_cast<std::uint64_t>(y);
      if (m.ann.area == 0 || m.end != i) {  // a new run of 1s after a run of 0s
        if (m.ann.area > 0) m.ann.rle.push_back(m.end - m.runStart);
        m.ann.rle.push_back(i - m.end);
        m.runStart = i;
      }
      m.end = i + 1;
      if (m.ann.area++ == 0) m.x0 = x, m.y0 = y;
      m.x0 = std::min(m.x0, x), m.y0 = std::min(m.y0, y), m.x1 = std::max(m.x1, x),
      m.y1 = std::max(m.y1, y);
    }
  const PhysicalCamera camera(d.camera);
  const double t = d.camera.shutter.centre();
  const std::uint64_t pixels =
      static_cast<std::uint64_t>(a.width) * static_cast<std::uint64_t>(a.height);
  std::vector<InstanceAnnotation> out;
  for (std::size_t s = 0; s < masks.size(); ++s) {
    Mask& m = masks[s];
    if (m.ann.area == 0) continue;
    m.ann.rle.push_back(m.end - m.runStart);
    if (m.end < pixels) m.ann.rle.push_back(pixels - m.end);
    const std::uint32_t cls = classes.ofShape[s];
    m.ann.instance = static_cast<std::uint32_t>(s + 1);
    m.ann.name = d.shapes[s].label;
    m.ann.category = classes.numbers[cls];
    m.ann.categoryName = classes.names[cls];
    m.ann.bbox = {m.x0, m.y0, m.x1 - m.x0 + 1, m.y1 - m.y0 + 1};
    m.ann.bbox3d = projectedBox(d.shapes[s], camera, t);
    out.push_back(std::move(m.ann));
  }
  return out;
}

}  // namespace camsim
