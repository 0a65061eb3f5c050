// The BOP layout's scene files and images (bop_writer.h); the models are bop_models.cpp's.
#include "integrator/capture/bop_writer.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "integrator/capture/matrix_rows.h"
#include "sensor/base/check.h"
#include "sensor/base/format.h"
#include "sensor/io/output_set.h"
#include "sensor/io/png_io.h"

namespace camsim {
namespace {

std::vector<double> millimetres(const glm::dvec3& v) {
  return {v.x * kMmPerM, v.y * kMmPerM, v.z * kMmPerM};
}

// A mask's pixels from a coverage channel: 0/255, its count and its bop_toolkit box.
struct Mask {
  std::vector<std::uint16_t> pixels;
  std::uint64_t count = 0;
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  std::string box() const {
    if (count == 0) return "[-1, -1, -1, -1]";
    return "[" + std::to_string(x0) + ", " + std::to_string(y0) + ", " + std::to_string(x1 - x0) +
           ", " + std::to_string(y1 - y0) + "]";
  }
};

Mask maskOf(const Image& aovs, int channel) {
  Mask m;
  m.pixels.assign(static_cast<std::size_t>(aovs.width) * static_cast<std::size_t>(aovs.height), 0);
  for (int y = 0; y < aovs.height; ++y)
    for (int x = 0; x < aovs.width; ++x) {
      if (!(double(aovs.at(x, y, channel)) >= kMaskCoverage)) continue;
      m.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(aovs.width) +
               static_cast<std::size_t>(x)] = 255;
      if (m.count++ == 0) m.x0 = m.x1 = x, m.y0 = m.y1 = y;
      m.x0 = std::min(m.x0, x), m.x1 = std::max(m.x1, x);
      m.y0 = std::min(m.y0, y), m.y1 = std::max(m.y1, y);
    }
  return m;
}

PngImage grey(const Image& like, std::vector<std::uint16_t> samples, int bitDepth) {
  PngImage png;
  png.width = like.width;
  png.height = like.height;
  png.channels = 1;
  png.bitDepth = bitDepth;
  png.samples = std::move(samples);
  return png;
}

}  // namespace

double bopDepthScale(double maxDepthMm) {
  double scale = 0.1;
  while (maxDepthMm / scale > 65535.0 && scale < 1e12) scale *= 10.0;
  return scale;
}

BopWriter::BopWriter(std::filesystem::path directory, int sceneId, const PoseModels& models)
    : directory_(std::move(directory)),
      scene_(directory_ / "bop" / "train_pbr" / formatSixDigits(sceneId)),
      models_(&models) {}

std::vector<std::filesystem::path> BopWriter::addFrame(const CaptureResult& r, int imageId) {
  const SceneDescription& d = r.description;
  // The run's models are this scene's (PoseModels of a scene with `exports: [bop]`).
  CAMSIM_CHECK(models_->bopOfShape().size() == d.shapes.size());
  const std::string image = formatSixDigits(imageId), key = std::to_string(imageId);
  const Image& a = r.aovs;
  // The camera at the frame's reference time: world (the scene file's) → camera, OpenCV.
  const PhysicalCamera camera(d.camera);
  const glm::dmat4 cameraFromRender = cameraCvFromRender(camera, d.camera.shutter.centre());
  glm::dmat4 cameraFromWorld = cameraFromRender;
  cameraFromWorld[3] -= cameraFromRender * glm::dvec4(d.renderOrigin, 0.0);
  const glm::dvec4& k = camera.intrinsics();
  const auto n = [](double v) { return formatShortest(v); };

  // depth/: camera-space z (depth.Z, m) in steps of depth_scale mm; 0 where nothing was hit.
  const int depthChannel = a.channelIndex("depth.Z");
  const std::size_t pixels = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
  std::vector<std::uint16_t> depth(pixels, 0);
  double maxDepth = 0.0;
  if (depthChannel >= 0)
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        maxDepth = std::max(maxDepth, double(a.at(x, y, depthChannel)));
  const double depthScale = bopDepthScale(maxDepth * kMmPerM);
  if (depthChannel >= 0)
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x) {
        const double z = double(a.at(x, y, depthChannel)) * kMmPerM / depthScale;
        if (z > 0.0 && std::isfinite(z))
          depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(a.width) +
                static_cast<std::size_t>(x)] =
              static_cast<std::uint16_t>(std::min(65535.0, std::round(z)));
      }
  camera_.set(key, JsonObject()
                       .setJson("cam_K", "[" + n(k.x) + ", 0, " + n(k.z) + ", 0, " + n(k.y) + ", " +
                                             n(k.w) + ", 0, 0, 1]")
                       .set("cam_R_w2c", rowMajor(glm::dmat3(cameraFromWorld)))
                       .set("cam_t_w2c", millimetres(glm::dvec3(cameraFromWorld[3])))
                       .setJson("depth_scale", n(depthScale)));

  const std::vector<ObjectPose> poses = objectPoses(d, d.camera, models_->bopOfShape());
  std::vector<JsonObject> gt, info;
  std::vector<std::pair<int, int>> channels;  // per annotation: amodal, visible
  for (const ObjectPose& p : poses) {
    gt.push_back(JsonObject()
                     .setInteger("obj_id", p.classNumber)
                     .set("cam_R_m2c", rowMajor(p.rotation))
                     .set("cam_t_m2c", millimetres(p.translation)));
    const std::string number = std::to_string(p.instance);
    channels.emplace_back(a.channelIndex("amodal_" + number + ".A"),
                          a.channelIndex("visible_" + number + ".A"));
    if (masks_ && (channels.back().first < 0 || channels.back().second < 0)) {
      masks_ = false;
      skipped_.push_back(
          "bop: mask/, mask_visib/ and scene_gt_info.json not written: the "
          "render has no amodal_" +
          number + ".A / visible_" + number + ".A channel (render.aovs: amodal)");
    }
  }
  gt_.set(key, gt);

  std::vector<std::filesystem::path> files;
  auto commit = [&](OutputSet& set) {
    for (auto& f : set.commit()) files.push_back(std::move(f));
  };
  (void)OutputSet::prepareDirectory(scene_ / "rgb");
  (void)OutputSet::prepareDirectory(scene_ / "depth");
  OutputSet rgb(scene_ / "rgb"), depthSet(scene_ / "depth");
  std::filesystem::copy_file(directory_ / (d.name + ".png"), rgb.add(image + ".png"),
                             std::filesystem::copy_options::overwrite_existing);
  if (depthChannel >= 0)
    writePng(depthSet.add(image + ".png"), grey(a, depth, 16));
  else
    skipped_.push_back("bop: depth/" + image + ".png not written: the render has no depth AOV");
  if (masks_) {
    (void)OutputSet::prepareDirectory(scene_ / "mask");
    (void)OutputSet::prepareDirectory(scene_ / "mask_visib");
    OutputSet amodal(scene_ / "mask"), visible(scene_ / "mask_visib");
    for (std::size_t g = 0; g < poses.size(); ++g) {
      Mask all = maskOf(a, channels[g].first);
      const Mask visib = maskOf(a, channels[g].second);
      std::uint64_t valid = 0;
      for (std::size_t i = 0; i < pixels; ++i) valid += all.pixels[i] && depth[i] > 0 ? 1 : 0;
      info.push_back(
          JsonObject()
              .setJson("bbox_obj", all.box())
              .setJson("bbox_visib", visib.box())
              .setInteger("px_count_all", all.count)
              .setInteger("px_count_valid", valid)
              .setInteger("px_count_visib", visib.count)
              .set("visib_fract", all.count > 0 ? double(visib.count) / double(all.count) : 0.0));
      const std::string name = image + "_" + formatSixDigits(static_cast<long long>(g)) + ".png";
      writePng(amodal.add(name), grey(a, std::move(all.pixels), 8));
      writePng(visible.add(name), grey(a, visib.pixels, 8));
    }
    gtInfo_.set(key, info);
    commit(amodal);
    commit(visible);
  }
  commit(rgb);
  commit(depthSet);
  return files;
}

std::vector<std::filesystem::path> BopWriter::finish() {
  std::vector<std::filesystem::path> files =
      writeBopModels(models_->bop(), directory_ / "bop" / "models");
  (void)OutputSet::prepareDirectory(scene_);
  OutputSet scene(scene_);
  scene.addText("scene_camera.json", camera_.str() + "\n");
  scene.addText("scene_gt.json", gt_.str() + "\n");
  if (masks_) scene.addText("scene_gt_info.json", gtInfo_.str() + "\n");
  for (auto& f : scene.commit()) files.push_back(std::move(f));
  return files;
}

std::vector<std::filesystem::path> writeBop(const CaptureResult& result, const PoseModels& models,
                                            const std::filesystem::path& directory, int sceneId,
                                            std::vector<std::string>* skipped) {
  BopWriter writer(directory, sceneId, models);
  std::vector<std::filesystem::path> files = writer.addFrame(result, 0);
  for (auto& f : writer.finish()) files.push_back(std::move(f));
  if (skipped) skipped->insert(skipped->end(), writer.skipped().begin(), writer.skipped().end());
  return files;
}

}  // namespace camsim
