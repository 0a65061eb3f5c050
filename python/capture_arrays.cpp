// The dict a capture returns (capture_arrays.h): NumPy arrays viewing CaptureBuffers without
// a copy (a capsule holding the shared owner is each array's base), and `meta` parsed from
// the library's own sidecar JSON. Shapes: images (height, width, channels) in row order top
// to bottom, one-channel layers (height, width); C-contiguous unless a view into interleaved
// channels (then strided, as the EXR layers are stored).
#include "python/capture_arrays.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "integrator/camera/physical_camera.h"
#include "integrator/capture/camera_export.h"
#include "integrator/capture/capture_sidecar.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/capture/dataset_writer.h"
#include "sensor/isp/color_management.h"

namespace camsim::python {
namespace {

namespace py = pybind11;
using Owner = std::shared_ptr<CaptureBuffers>;

// An array over `data` that keeps `owner` alive: the capsule owns a heap copy of the shared
// pointer and deletes it when NumPy drops the array (ownership passes to the capsule).
template <typename T>
py::array view(const Owner& owner, const T* data, std::vector<py::ssize_t> shape,
               std::vector<py::ssize_t> stridesInElements) {
  std::vector<py::ssize_t> strides;
  for (py::ssize_t s : stridesInElements)
    strides.push_back(s * static_cast<py::ssize_t>(sizeof(T)));
  auto keep = std::make_unique<Owner>(owner);
  py::capsule base(keep.get(), [](void* p) { std::unique_ptr<Owner>(static_cast<Owner*>(p)); });
  keep.release();  // now the capsule's
  return py::array(py::dtype::of<T>(), std::move(shape), std::move(strides), data, base);
}

// Channels [first, first + count) of an interleaved image: (h, w, count), or (h, w) for one.
py::array channels(const Owner& o, const Image& img, int first, int count) {
  const py::ssize_t h = img.height, w = img.width, c = img.channelCount();
  const float* data = img.pixels.data() + first;
  if (count == 1) return view(o, data, {h, w}, {w * c, c});
  return view(o, data, {h, w, count}, {w * c, c, 1});
}

py::array image(const Owner& o, const Image& img) {
  return channels(o, img, 0, img.channelCount());
}

// A raw frame's planes: a mosaic's (h, w) array, a stacked sensor's dict plane → (h, w).
py::object raws(const Owner& o, const CaptureFrame& f, const SensorSettings& sensor) {
  const auto plane = [&](const RawImage& r) {
    return view(o, r.dn.data(), {r.height, r.width}, {r.width, 1});
  };
  if (!sensor.spec.cfa.isStacked()) return plane(f.raws.front());
  py::dict out;
  for (std::size_t c = 0; c < f.raws.size(); ++c)
    out[py::str(sensor.spec.cfa.channels[c])] = plane(f.raws[c]);
  return out;
}

// The AOV image's layers: consecutive channels with the same name before the last '.'
// (depth.Z → "depth", P.X/Y/Z → "P", CryptoObject00.R/G/B/A → "CryptoObject00"); the ids
// ("instance.id", …) as uint32.
py::dict aovLayers(const Owner& o) {
  py::dict out;
  const Image& a = o->result.aovs;
  int c = 0;
  while (c < a.channelCount()) {
    const std::string& name = a.channels[static_cast<std::size_t>(c)];
    const std::string layer = name.substr(0, name.rfind('.'));
    int n = 1;
    while (c + n < a.channelCount()) {
      const std::string& next = a.channels[static_cast<std::size_t>(c + n)];
      if (next.substr(0, next.rfind('.')) != layer) break;
      ++n;
    }
    out[py::str(layer)] = channels(o, a, c, n);
    c += n;
  }
  for (std::size_t i = 0; i < o->idLayers.size(); ++i) {
    const std::string& name = o->idLayers[i];
    out[py::str(name.substr(0, name.rfind('.')))] =
        view(o, o->ids[i].data(), {a.height, a.width}, {a.width, 1});
  }
  return out;
}

}  // namespace

void deriveBuffers(CaptureBuffers& b, const PictureSettings& picture) {
  const CaptureResult& r = b.result;
  b.filmExr = xyzExrImage(r.film);
  const OcioProcessor ocio(picture.ocioConfig);
  b.choice = ocio.resolve(picture.choice);
  b.ocioConfig = ocio.location().path.string();
  b.display = ocio.toDisplay(r.picture, b.choice);
  b.display8 = quantizeDisplay8(b.display.pixels);
  const Image& a = r.aovs;
  for (int c = 0; c < a.channelCount(); ++c) {
    const std::string& name = a.channels[static_cast<std::size_t>(c)];
    if (name.size() < 3 || name.compare(name.size() - 3, 3, ".id") != 0) continue;
    std::vector<std::uint32_t> ids(static_cast<std::size_t>(a.width) *
                                   static_cast<std::size_t>(a.height));
    for (std::size_t p = 0; p < ids.size(); ++p)
      ids[p] =
          static_cast<std::uint32_t>(a.pixels[p * a.channels.size() + static_cast<std::size_t>(c)]);
    b.idLayers.push_back(name);
    b.ids.push_back(std::move(ids));
  }
  b.sidecarJson = captureSidecar(r, true).str();
  // The pose and intrinsics as cameras.json writes them (dataset_writer.h).
  const DatasetFrame frame = datasetFrame(r);
  const PhysicalCamera camera(frame.camera);
  const glm::dmat4 cv = worldFromCameraOpenCv(frame, camera);
  std::vector<std::vector<double>> rows(4, std::vector<double>(4));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = cv[j][i];
  const glm::dvec4 k = camera.intrinsics();
  JsonObject pose;
  // The camera model and its coefficients as cameras.json writes them (camera_export.h).
  JsonObject model;
  addCameraModel(model, cameraExport(camera));
  pose.set("world_from_camera_opencv", rows)
      .set("opencv_fx_fy_cx_cy", std::vector<double>{k.x, k.y, k.z, k.w})
      .set("projection", model)
      .set("reference_time_s", frame.camera.shutter.centre())
      .set("exposure_time_s", frame.exposureTimeS);
  // Without a sensor there is no ISO nor gain: None (cameras.json writes 0 there).
  if (r.description.sensor)
    pose.set("iso", frame.isoValue).set("system_gain_dn_per_e", frame.systemGainDnPerE);
  else
    pose.setJson("iso", "null").setJson("system_gain_dn_per_e", "null");
  b.posesJson = pose.str();
}

py::dict captureDict(const Owner& o) {
  const CaptureResult& r = o->result;
  py::dict out;
  out["xyz"] = image(o, r.film);
  out["rgb"] = channels(o, o->filmExr, 0, 3);
  out["acescg"] = image(o, r.picture);
  out["display"] = image(o, o->display);
  out["display8"] = view(o, o->display8.data(), {o->display.height, o->display.width, 3},
                         {o->display.width * 3, 3, 1});
  if (r.description.sensor && !r.frames.empty()) {
    const SensorSettings& sensor = *r.description.sensor;
    py::list brackets;
    for (const CaptureFrame& f : r.frames) {
      py::dict b;
      b["ev"] = f.ev;
      b["exposure_time_s"] = f.exposureTimeS;
      b["frame_index"] = f.frameIndex;
      b["white_balance_gains"] = py::cast(f.whiteBalanceGains);
      b["clipped_fraction"] = f.clippedFraction;
      b["electrons"] = image(o, f.electrons);
      b["raw"] = raws(o, f, sensor);
      brackets.append(b);
    }
    out["brackets"] = brackets;
    out["electrons"] = brackets[r.referenceFrame]["electrons"];
    out["raw"] = brackets[r.referenceFrame]["raw"];
    out["sensor_film"] = image(o, r.sensorFilm);
  }
  if (!r.aovs.pixels.empty()) out["aovs"] = aovLayers(o);
  if (!r.sampleCounts.pixels.empty()) out["spp"] = image(o, r.sampleCounts);
  const py::module_ json = py::module_::import("json");
  py::dict meta = json.attr("loads")(o->sidecarJson);
  meta["pose"] = json.attr("loads")(o->posesJson);
  py::dict color;
  color["config"] = o->ocioConfig;
  color["display"] = o->choice.display;
  color["view"] = o->choice.view;
  color["look"] = o->choice.looks;
  meta["color"] = color;
  meta["reference_frame"] = r.referenceFrame;
  meta["threads"] = r.stats.threads;         // the render's worker threads
  meta["render_seconds"] = r.stats.seconds;  // wall time (not in the reproducible sidecar)
  // Whether the render ran on the Scene's renderable scene (BVH) built by an earlier
  // capture, not a new one (capture(reuse=)): the renderer says what it modelled.
  meta["scene_reused"] = r.sceneReused;
  out["meta"] = meta;
  return out;
}

}  // namespace camsim::python
