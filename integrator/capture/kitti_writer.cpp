#include "integrator/capture/kitti_writer.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "integrator/capture/object_poses.h"
#include "sensor/base/format.h"
#include "sensor/io/output_set.h"

namespace camsim {
namespace {

constexpr double kNearest = 0.1;             // m: a box corner nearer the camera is left out
constexpr double kUprightCos = 0.984807753;  // cos 10°

double wrapAngle(double a) {
  while (a > std::numbers::pi) a -= 2.0 * std::numbers::pi;
  while (a < -std::numbers::pi) a += 2.0 * std::numbers::pi;
  return a;
}

// KITTI's rect frame in camera (OpenCV) axes: its columns x, y, z — y down along gravity
// (render space's −y), z the camera's forward made level, x = y × z.
glm::dmat3 cameraFromRect(const glm::dmat4& cameraFromRender) {
  const glm::dvec3 down = glm::normalize(glm::dmat3(cameraFromRender) * glm::dvec3(0, -1, 0));
  glm::dvec3 forward = glm::dvec3(0, 0, 1) - down * down.z;
  // A camera looking straight down (up): forward is where the image's top (bottom) faces, the
  // limit of a camera tilted ever further — its −y (+y).
  if (glm::length(forward) < 1e-9)
    forward = glm::dvec3(0, down.z > 0.0 ? -1.0 : 1.0, 0) - down * down.y;
  forward = glm::normalize(forward);
  return glm::dmat3(glm::cross(down, forward), down, forward);
}

// Per pose: the fraction of its object's amodal mask that is visible (both masks: coverage
// ≥ ½), or none without the channels or with an empty amodal mask. One pass over the image
// counts every object's pixels.
std::vector<std::optional<double>> visibleFractions(const Image& a,
                                                    const std::vector<ObjectPose>& poses) {
  struct Counts {
    int amodal = -1, visible = -1;  // channels
    std::uint64_t all = 0, seen = 0;
  };
  std::vector<Counts> counts;                               // the poses with both channels
  std::vector<std::size_t> of(poses.size(), poses.size());  // per pose: its counts' index
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::string n = std::to_string(poses[i].instance);
    const int am = a.channelIndex("amodal_" + n + ".A"), vi = a.channelIndex("visible_" + n + ".A");
    if (am < 0 || vi < 0) continue;
    of[i] = counts.size();
    counts.push_back(Counts{am, vi, 0, 0});
  }
  if (!counts.empty())
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        for (Counts& c : counts) {
          c.all += static_cast<double>(a.at(x, y, c.amodal)) >= kMaskCoverage ? 1 : 0;
          c.seen += static_cast<double>(a.at(x, y, c.visible)) >= kMaskCoverage ? 1 : 0;
        }
  std::vector<std::optional<double>> out(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
    if (of[i] < counts.size() && counts[of[i]].all > 0)
      out[i] = static_cast<double>(counts[of[i]].seen) / static_cast<double>(counts[of[i]].all);
  return out;
}

std::string typeOf(const ShapeDescription& s) {
  if (s.classNumber && std::to_string(*s.classNumber) == s.className) return "Class" + s.className;
  // Every whitespace character (a label line's fields are whitespace-separated: found by
  // probing, a tab or newline in a class name broke the line in two).
  std::string t = s.className;
  std::replace_if(
      t.begin(), t.end(), [](unsigned char c) { return std::isspace(c) != 0; }, '_');
  return t;
}

std::string line(const std::string& key, const double* m, int n) {
  std::string s = key + ":";
  for (int i = 0; i < n; ++i) s += " " + formatNumber(m[i], 12);
  return s + "\n";
}

}  // namespace

KittiFrame kittiFrame(const CaptureResult& result, std::span<const ObjectModel* const> models) {
  const SceneDescription& d = result.description;
  const PhysicalCamera camera(d.camera);
  const glm::dmat4 cameraFromRender = cameraCvFromRender(camera, d.camera.shutter.centre());
  const glm::dmat3 camRect = cameraFromRect(cameraFromRender);
  const glm::dmat3 rectCam = glm::transpose(camRect);
  const glm::dvec4 k = camera.intrinsics();                               // fx, fy, cx, cy
  const glm::dmat3 kMatrix(k.x, 0.0, 0.0, 0.0, k.y, 0.0, k.z, k.w, 1.0);  // columns
  const glm::dmat3 kr = kMatrix * camRect;
  KittiFrame f;
  f.p2.assign(12, 0.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) f.p2[static_cast<std::size_t>(4 * r + c)] = kr[c][r];
  const double w = d.camera.resolution.x, h = d.camera.resolution.y;
  // How far the camera is turned from rect, pitch and roll together: the rotation's angle
  // (found by probing: the forward axis alone missed an 11° roll, P2 no longer K).
  const double trace = camRect[0].x + camRect[1].y + camRect[2].z;
  const double tilt =
      std::acos(std::clamp(0.5 * (trace - 1.0), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  if (tilt > 1.0)
    f.skipped.push_back("kitti: the camera is " + formatNumber(tilt, 3) +
                        "° off level (pitched or rolled): P2 = K R (rect stays level), so a "
                        "reader that takes fx, fy, "
                        "cx, cy from P2's entries needs K from cameras.json or NAME.json instead");

  const std::vector<ObjectPose> poses = objectPoses(d, d.camera, models);
  const std::vector<std::optional<double>> visible = visibleFractions(result.aovs, poses);
  for (std::size_t g = 0; g < poses.size(); ++g) {
    const ObjectPose& pose = poses[g];
    const ShapeDescription& s = d.shapes[pose.shape];
    const glm::dmat3 rectFromModel = rectCam * pose.rotation;
    const glm::dvec3 tRect = rectCam * pose.translation;
    KittiLabel l;
    l.type = typeOf(s);
    l.h = pose.boxMax.y - pose.boxMin.y;
    l.w = pose.boxMax.z - pose.boxMin.z;
    l.l = pose.boxMax.x - pose.boxMin.x;
    const glm::dvec3 bottom(0.5 * (pose.boxMin.x + pose.boxMax.x), pose.boxMin.y,
                            0.5 * (pose.boxMin.z + pose.boxMax.z));
    const glm::dvec3 at = rectFromModel * bottom + tRect;
    l.x = at.x;
    l.y = at.y;
    l.z = at.z;
    const glm::dvec3 ax = rectFromModel * glm::dvec3(1, 0, 0);
    l.rotationY = std::atan2(-ax.z, ax.x);  // in [−π, π]
    l.alpha = wrapAngle(l.rotationY - std::atan2(l.x, l.z));
    if (glm::dot(rectFromModel * glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0)) < kUprightCos)
      f.skipped.push_back("kitti: '" + s.label +
                          "' is not upright (its model's y more than 10° from up): its box is "
                          "labelled turned into rect");
    // The KITTI box as a devkit reader builds it, through P2.
    const double c = std::cos(l.rotationY), sn = std::sin(l.rotationY);
    glm::dvec2 lo(1e300), hi(-1e300);
    bool behind = false;
    for (int i = 0; i < 8; ++i) {
      const double lx = (i & 1 ? 0.5 : -0.5) * l.l, lz = (i & 2 ? 0.5 : -0.5) * l.w;
      const double ly = i & 4 ? -l.h : 0.0;
      const glm::dvec3 p(c * lx + sn * lz + l.x, ly + l.y, -sn * lx + c * lz + l.z);
      const glm::dvec3 q = kr * p;
      // Behind the camera's plane, or behind rect's (where devkit readers drop a box).
      if ((camRect * p).z < kNearest || p.z < kNearest) behind = true;
      const glm::dvec2 uv(q.x / q.z, q.y / q.z);
      lo = glm::min(lo, uv);
      hi = glm::max(hi, uv);
    }
    if (behind) {
      f.skipped.push_back("kitti: '" + s.label + "' left out: its box reaches behind the camera");
      continue;
    }
    const double boxArea = (hi.x - lo.x) * (hi.y - lo.y);
    const double inW = std::max(0.0, std::min(hi.x, w - 0.5) - std::max(lo.x, -0.5));
    const double inH = std::max(0.0, std::min(hi.y, h - 0.5) - std::max(lo.y, -0.5));
    // Outside the image (no note): the clipped box would have no width or height.
    if (std::min(hi.x, w - 1.0) <= std::max(lo.x, 0.0) ||
        std::min(hi.y, h - 1.0) <= std::max(lo.y, 0.0))
      continue;
    l.truncated = boxArea > 0.0 ? std::clamp(1.0 - inW * inH / boxArea, 0.0, 1.0) : 0.0;
    l.left = std::clamp(lo.x, 0.0, w - 1.0);
    l.right = std::clamp(hi.x, 0.0, w - 1.0);
    l.top = std::clamp(lo.y, 0.0, h - 1.0);
    l.bottom = std::clamp(hi.y, 0.0, h - 1.0);
    const std::optional<double>& v = visible[g];
    l.occluded = !v ? 3 : *v >= 0.95 ? 0 : *v >= 0.5 ? 1 : 2;
    f.labels.push_back(l);
  }
  return f;
}

std::vector<std::filesystem::path> writeKittiFrame(const CaptureResult& result,
                                                   std::span<const ObjectModel* const> models,
                                                   const std::filesystem::path& directory,
                                                   int imageId, std::vector<std::string>* skipped) {
  const KittiFrame f = kittiFrame(result, models);
  const std::filesystem::path root = directory / "kitti";
  std::string calib;
  for (const char* p : {"P0", "P1", "P2", "P3"}) calib += line(p, f.p2.data(), 12);
  const double identity3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double identity34[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  calib += line("R0_rect", identity3, 9);
  calib += line("Tr_velo_to_cam", identity34, 12);
  calib += line("Tr_imu_to_velo", identity34, 12);
  std::string labels;
  for (const KittiLabel& l : f.labels) {
    const auto n = [](double v) { return formatNumber(v, 8); };
    labels += l.type + " " + n(l.truncated) + " " + std::to_string(l.occluded) + " " + n(l.alpha) +
              " " + n(l.left) + " " + n(l.top) + " " + n(l.right) + " " + n(l.bottom) + " " +
              n(l.h) + " " + n(l.w) + " " + n(l.l) + " " + n(l.x) + " " + n(l.y) + " " + n(l.z) +
              " " + n(l.rotationY) + "\n";
  }
  // All three written, then committed together: no image without its calib and labels.
  const std::string name = formatSixDigits(imageId);
  for (const char* sub : {"image_2", "calib", "label_2"})
    (void)OutputSet::prepareDirectory(root / sub);
  OutputSet image(root / "image_2"), calibSet(root / "calib"), labelSet(root / "label_2");
  std::filesystem::copy_file(directory / (result.description.name + ".png"),
                             image.add(name + ".png"),
                             std::filesystem::copy_options::overwrite_existing);
  calibSet.addText(name + ".txt", calib);
  labelSet.addText(name + ".txt", labels);
  std::vector<std::filesystem::path> files;
  for (OutputSet* set : {&image, &calibSet, &labelSet})
    for (auto& file : set->commit()) files.push_back(std::move(file));
  if (skipped) skipped->insert(skipped->end(), f.skipped.begin(), f.skipped.end());
  return files;
}

}  // namespace camsim
