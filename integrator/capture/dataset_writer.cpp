#include "integrator/capture/dataset_writer.h"

#include <cmath>
#include <cstdio>
#include <map>

#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/capture/camera_export.h"
#include "integrator/capture/matrix_rows.h"
#include "integrator/capture/object_poses.h"
#include "sensor/io/json_writer.h"
#include "sensor/io/output_set.h"

namespace camsim {
namespace {

// OpenGL / Blender axes: x right, y up, z backward.
glm::dmat4 toOpenGl(glm::dmat4 m) {
  m[1] = -m[1];
  m[2] = -m[2];
  return m;
}

std::string fixed(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

std::vector<double> box(const glm::dvec4& b) {
  return {b.x, b.y, b.z, b.w};
}

// COCO: one image per frame (id = frame index + 1), the classes seen as categories, one
// annotation per frame and visible labelled instance.
std::string cocoJson(const std::vector<DatasetFrame>& frames) {
  std::vector<JsonObject> images, annotations, categories;
  std::map<std::uint32_t, std::string> seen;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const DatasetFrame& f = frames[i];
    images.push_back(JsonObject()
                         .set("id", double(i + 1))
                         .set("file_name", f.image)
                         .set("width", double(f.camera.resolution.x))
                         .set("height", double(f.camera.resolution.y)));
    for (const InstanceAnnotation& a : f.annotations) {
      seen.emplace(a.category, a.categoryName);
      std::vector<double> counts(a.rle.begin(), a.rle.end());
      JsonObject j;
      j.set("id", double(annotations.size() + 1))
          .set("image_id", double(i + 1))
          .set("category_id", double(a.category))
          .set("bbox", box(a.bbox))
          .set("area", double(a.area))
          .set("iscrowd", 0.0)
          .set("segmentation", JsonObject()
                                   .set("size", std::vector<double>{double(f.camera.resolution.y),
                                                                    double(f.camera.resolution.x)})
                                   .set("counts", counts))
          .set("instance_id", double(a.instance))
          .set("instance_name", a.name);
      if (a.bbox3d) j.set("bbox_3d", box(*a.bbox3d));
      annotations.push_back(std::move(j));
    }
  }
  for (const auto& [id, name] : seen)
    categories.push_back(JsonObject().set("id", double(id)).set("name", name));
  return JsonObject()
             .set("info", JsonObject().set("description",
                                           "camsim ground truth: boxes and masks from the "
                                           "dominant instance ids (docs/output.md)"))
             .set("images", images)
             .set("categories", categories)
             .set("annotations", annotations)
             .str() +
         "\n";
}

}  // namespace

DatasetFrame datasetFrame(const CaptureResult& r) {
  DatasetFrame f;
  f.image = r.description.name + ".png";
  f.camera = r.description.camera;
  f.renderOrigin = r.description.renderOrigin;
  f.exposureTimeS = r.description.camera.shutter.effectiveTime();
  f.annotated = r.aovs.channelIndex("instance.id") >= 0;
  f.annotations = annotateFrame(r);
  if (r.description.sensor) {
    f.isoValue = r.description.sensor->iso;
    f.systemGainDnPerE = r.description.sensor->spec.systemGain(f.isoValue);
    if (!r.frames.empty()) f.exposureTimeS = r.frames[r.referenceFrame].exposureTimeS;
  }
  return f;
}

glm::dmat4 worldFromCameraOpenCv(const DatasetFrame& frame, const PhysicalCamera& camera) {
  glm::dmat4 m = renderFromCameraCv(camera, frame.camera.shutter.centre());
  m[3] += glm::dvec4(frame.renderOrigin, 0.0);  // render → world
  return m;
}

std::vector<std::filesystem::path> writeDatasetMetadata(const std::vector<DatasetFrame>& frames,
                                                        const std::filesystem::path& directory,
                                                        std::vector<std::string>* skipped) {
  std::vector<JsonObject> cameraFrames, nerfFrames;
  std::vector<CameraExport> exports;  // per frame: the model in each tool's terms
  std::string images;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const DatasetFrame& f = frames[i];
    const PhysicalCamera camera(f.camera);
    const CameraExport& e = exports.emplace_back(cameraExport(camera));
    const PhysicalCameraParams& p = f.camera;
    const glm::dmat4 cv = worldFromCameraOpenCv(f, camera);
    JsonObject frame;
    frame.set("image", f.image)
        .set("width", double(p.resolution.x))
        .set("height", double(p.resolution.y))
        .setExact("fx", e.fx)
        .setExact("fy", e.fy)
        .setExact("cx", e.cx)
        .setExact("cy", e.cy);
    addCameraModel(frame, e);
    // Poses exactly: 10 digits put a camera at 1.2e8 m 2.3 cm off (found by probing; scenes
    // allow coordinates to 1e15 m).
    cameraFrames.push_back(frame.setExact("world_from_camera_opencv", matrixRows(cv))
                               .setExact("world_from_camera_opengl", matrixRows(toOpenGl(cv)))
                               .set("time_s", p.shutter.centre())
                               .set("shutter_open_s", p.shutter.open())
                               .set("shutter_close_s", p.shutter.close())
                               .set("row_time_s", p.shutter.rowTime())
                               .set("readout_s", p.shutter.rowTime() * p.resolution.y)
                               .set("exposure_time_s", f.exposureTimeS)
                               .set("f_number", p.fNumber)
                               .set("iso", f.isoValue)
                               .set("system_gain_dn_per_e", f.systemGainDnPerE));
    nerfFrames.push_back(JsonObject()
                             .set("file_path", f.image)
                             .setExact("transform_matrix", matrixRows(toOpenGl(cv))));
    // COLMAP: camera-from-world (OpenCV axes) as a unit quaternion and translation.
    const glm::dmat3 worldFromCam(cv);
    const glm::dmat3 camFromWorld = glm::transpose(worldFromCam);
    const glm::dquat q = glm::quat_cast(camFromWorld);
    const glm::dvec3 t = -(camFromWorld * glm::dvec3(cv[3]));
    images += std::to_string(i + 1) + " " + fixed(q.w) + " " + fixed(q.x) + " " + fixed(q.y) + " " +
              fixed(q.z) + " " + fixed(t.x) + " " + fixed(t.y) + " " + fixed(t.z) + " " +
              std::to_string(i + 1) + " " + f.image + "\n\n";
  }
  // An export whose tool cannot express a frame's model is left out, and cameras.json and
  // the caller (the run's output) say why.
  std::string colmapLacks, nerfLacks;
  for (const CameraExport& e : exports) {
    if (colmapLacks.empty()) colmapLacks = e.colmapLacks;
    if (nerfLacks.empty()) nerfLacks = e.nerfstudioLacks;
  }
  JsonObject notWritten;
  if (!colmapLacks.empty()) notWritten.set("colmap", colmapLacks);
  if (!nerfLacks.empty()) notWritten.set("transforms.json", nerfLacks);
  if (skipped) {
    if (!colmapLacks.empty()) skipped->push_back("colmap/ not written: " + colmapLacks);
    if (!nerfLacks.empty()) skipped->push_back("transforms.json not written: " + nerfLacks);
  }
  JsonObject cameras;
  if (!colmapLacks.empty() || !nerfLacks.empty()) cameras.set("not_written", notWritten);
  cameras
      .set("convention",
           "world_from_camera_opencv: columns x right, y down, z forward, position (m, the "
           "scene's world); _opengl: x right, y up, z backward; cx, cy with pixel centres at "
           "integers; pose at time_s, the shutter window's centre (row 0); model and its "
           "coefficients as camera.projection (docs/camera.md), in OpenCV's order")
      .set("frames", cameraFrames);
  const DatasetFrame& first = frames.front();
  const CameraExport& e0 = exports.front();
  JsonObject nerf;
  nerf.set("camera_model", e0.nerfstudioModel);
  for (const auto& [key, value] : e0.nerfstudio) nerf.setExact(key, value);
  nerf.set("w", double(first.camera.resolution.x))
      .set("h", double(first.camera.resolution.y))
      .setExact("camera_angle_x", e0.cameraAngleX)
      .set("frames", nerfFrames);
  // One COLMAP camera per frame (a frame's intrinsics may differ: focus, resolution).
  std::string camerasTxt =
      "# CAMERA_ID MODEL WIDTH HEIGHT PARAMS[] (fx fy cx cy, then the "
      "model's: OPENCV k1 k2 p1 p2; FULL_OPENCV k1 k2 p1 p2 k3 k4 k5 k6; "
      "OPENCV_FISHEYE k1 k2 k3 k4)\n";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const PhysicalCameraParams& p = frames[i].camera;
    camerasTxt += std::to_string(i + 1) + " " + exports[i].colmapModel + " " +
                  std::to_string(p.resolution.x) + " " + std::to_string(p.resolution.y);
    for (double v : exports[i].colmapParams) camerasTxt += " " + fixed(v);
    camerasTxt += "\n";
  }
  std::vector<std::filesystem::path> files;
  if (colmapLacks.empty()) {
    // colmap/ is a set of its own (OutputSet names temporaries beside their final names).
    std::filesystem::create_directories(directory / "colmap");
    OutputSet colmap(directory / "colmap");
    colmap.addText("cameras.txt", camerasTxt);
    colmap.addText(
        "images.txt",
        "# IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME (then a line of points)\n" + images);
    colmap.addText("points3D.txt", "# no points: poses and intrinsics only\n");
    files = colmap.commit();
  }
  OutputSet outputs(directory);
  outputs.addText("cameras.json", cameras.str() + "\n");
  if (nerfLacks.empty()) outputs.addText("transforms.json", nerf.str() + "\n");
  if (first.annotated) outputs.addText("annotations.json", cocoJson(frames));
  for (auto& f : outputs.commit()) files.push_back(std::move(f));
  return files;
}

}  // namespace camsim
