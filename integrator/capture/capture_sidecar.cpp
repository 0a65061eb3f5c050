#include "integrator/capture/capture_sidecar.h"

#include <algorithm>

#include <string>
#include <vector>

#include "integrator/camera/physical_camera.h"
#include "integrator/render/cryptomatte.h"
#include "integrator/scene/scene_ids.h"
#include "sensor/model/exposure_control.h"
#include "sensor/model/sensor_model.h"

namespace camsim {
namespace {

std::vector<double> matrixRows(const glm::dmat3& m) {
  std::vector<double> v;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v.push_back(m[c][r]);
  return v;
}

JsonObject cameraJson(const PhysicalCamera& camera) {
  const PhysicalCameraParams& p = camera.params();
  const glm::dvec4 k = camera.intrinsics();
  JsonObject j;
  j.set("resolution", std::vector<double>{double(p.resolution.x), double(p.resolution.y)})
      .set("sensor_size_m", std::vector<double>{p.sensorSize.x, p.sensorSize.y})
      .set("fill_factor", p.fillFactor)
      .set("focal_length_m", p.focalLength)
      .set("f_number", p.fNumber);
  // Focus at infinity (focusDistance 0 in PhysicalCameraParams) is null: no distance.
  if (p.focusDistance > 0.0)
    j.set("focus_distance_m", p.focusDistance);
  else
    j.setJson("focus_distance_m", "null");
  j.set("image_distance_m", camera.imageDistance())
      .set("aperture",
           p.aperture
               ? (p.aperture->blades ? std::to_string(p.aperture->blades) + " blades" : "circular")
               : "pinhole")
      .set("pupil", p.pupil == LensPupil::kFlat ? "flat" : "aplanatic")
      .set("shutter_open_s", p.shutter.open())
      .set("shutter_close_s", p.shutter.close())
      .set("exposure_time_s", p.shutter.effectiveTime())
      .set("rolling_shutter_row_time_s", p.shutter.rowTime())
      .set("opencv_fx_fy_cx_cy", std::vector<double>{k.x, k.y, k.z, k.w})
      .set("opencv_k1_k2_p1_p2_k3",
           std::vector<double>{p.distortion.k1, p.distortion.k2, p.distortion.p1, p.distortion.p2,
                               p.distortion.k3});
  return j;
}

JsonObject sensorJson(const CaptureResult& r) {
  const SensorSettings& sensor = *r.description.sensor;
  std::vector<double> evs, times;
  for (const CaptureFrame& f : r.frames) evs.push_back(f.ev), times.push_back(f.exposureTimeS);
  JsonObject j;
  j.set("model", sensor.spec.name)
      .set("iso", sensor.iso)
      .set("noise", noiseModeName(sensor.noise))
      .setInteger("noise_seed", sensor.noiseSeed)
      .set("frame", double(sensor.frame))
      .set("auto_exposure",
           sensor.autoExposure ? meteringName(sensor.autoExposure->metering) : "off")
      .set("auto_exposure_scale", r.exposureScale)
      .set("bracket_ev", evs)
      .set("exposure_times_s", times)
      .set("system_gain_dn_per_e", sensor.spec.systemGain(sensor.iso))
      .set("saturation_e", sensor.spec.saturationElectrons(sensor.iso));
  return j;
}

JsonObject ispJson(const CaptureResult& r) {
  const IspSettings& isp = r.description.isp;
  const DevelopedImage& dev = *r.developed;
  const char* wb[] = {"illuminant", "region", "grey_world"};
  JsonObject j;
  j.set("white_balance", wb[static_cast<int>(isp.whiteBalance)])
      .set("illuminant", isp.illuminant)
      .set("white_balance_gains", dev.whiteBalance)
      .set("chromatic_adaptation",
           r.description.sensor->spec.cfa.isStacked()
               ? "Bradford from the white's XYZ to D65 (ccm_camera_to_xyz_d65)"
               : "Bradford to D65, in the CCM fit")
      .set("demosaic",
           isp.demosaic == DemosaicMethod::kMalvarHeCutler ? "malvar-he-cutler" : "bilinear")
      .set("ccm_camera_to_xyz_d65", matrixRows(dev.colorCorrection.cameraToXyz))
      .set("xyz_d65_to_working", matrixRows(dev.colorCorrection.xyzToWorking))
      .set("working_space", "ACEScg");
  return j;
}

std::vector<std::string> aovNames(const std::vector<Aov>& aovs) {
  std::vector<std::string> names;
  for (Aov a : aovs) names.emplace_back(aovName(a));
  return names;
}

// The id tables of the scene's id aovs: per kind, each entry's dominant-id number, name
// and Cryptomatte id (the hex of the float, as in the EXR manifest).
JsonObject idsJson(const SceneDescription& desc) {
  JsonObject j;
  const SceneIds ids = sceneIds(desc);
  for (IdKind k : idKindsOf(desc.render.aovs)) {
    std::vector<JsonObject> entries;
    const IdTable& t = ids[k];
    for (std::size_t e = 1; e < t.names.size(); ++e)
      entries.push_back(JsonObject()
                            .set("number", double(t.numbers[e]))
                            .set("name", t.names[e])
                            .set("cryptomatte", cryptomatteHex(cryptomatteId(t.names[e]))));
    j.set(idKindName(k),
          JsonObject().set("cryptomatte_type", cryptomatteTypeName(k)).set("entries", entries));
  }
  return j;
}

}  // namespace

JsonObject captureSidecar(const CaptureResult& r, bool reproducible) {
  const SceneDescription& desc = r.description;
  const RenderStats& st = r.stats;
  std::vector<std::string> inputFiles;
  for (const auto& f : desc.inputFiles) inputFiles.push_back(f.string());
  JsonObject render;
  render.set("spp", double(desc.render.spp))
      .setInteger("seed", desc.render.seed)
      .set("sampler", samplerName(desc.render.sampler))
      .set("max_depth", double(desc.render.maxDepth));
  if (!reproducible) render.set("seconds", st.seconds);
  render.set("rejected_samples", double(st.rejectedSamples))
      .set("modelled", st.modelled.describe())
      .set("aovs", aovNames(desc.render.aovs))
      .set("ids", idsJson(desc));
  JsonObject sidecar;
  sidecar.set("camsim_version", CAMSIM_VERSION)
      .set("scene", desc.sourceFile)
      .set("input_files", inputFiles)
      .set("import_notes", desc.notes)  // always present, [] when the loader noted nothing
      .set("render", render)
      .set("camera", cameraJson(PhysicalCamera(desc.camera)));
  if (desc.sensor)
    sidecar.set("sensor", sensorJson(r)).set("isp", ispJson(r));
  else
    sidecar.set("display_exposure", r.displayExposure);
  return sidecar;
}

}  // namespace camsim
