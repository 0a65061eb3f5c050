#include "integrator/capture/capture_sidecar.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/trigonometric.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/capture/camera_export.h"
#include "integrator/capture/matrix_rows.h"
#include "integrator/render/cryptomatte.h"
#include "integrator/scene/scene_ids.h"
#include "sensor/base/format.h"
#include "sensor/model/exposure_control.h"
#include "sensor/model/sensor_model.h"

namespace camsim {
namespace {

// The scene inputs below are written in shortest round-trip form (setExact, formatShortest):
// they must paste back into a scene and give the same bytes (JsonObject::set keeps 10 digits).

// A length in m as the scene's mm: the loader keeps float(mm · 1e-3) (positiveFloat), so
// 85 mm is 0.08500000089406967 m. The shortest float text ("85") when it reads back to the
// same metres, else the exact double (still the same metres, less readable).
std::string millimetres(double metres) {
  char buffer[32];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(metres * 1e3));
  const std::string text(buffer, result.ptr);
  double mm = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), mm);
  if (static_cast<double>(static_cast<float>(mm * 1e-3)) == metres) return text;
  return formatShortest(metres * 1e3);
}

// The camera's `shutter:` as a scene writes it: open/close for a box, else its curve.
JsonObject shutterJson(const Shutter& shutter) {
  JsonObject j;
  j.set("type", std::string(enumName(shutter.type())));
  if (shutter.type() == Shutter::Type::kRolling) j.setExact("row_time", shutter.rowTime());
  const std::vector<double>& t = shutter.times();
  const std::vector<double>& s = shutter.values();
  if (t.size() == 2 && s[0] == 1.0 && s[1] == 1.0) {
    j.setExact("open", t[0]).setExact("close", t[1]);
  } else {
    std::string curve = "[";
    for (std::size_t i = 0; i < t.size(); ++i)
      curve += (i ? ", [" : "[") + formatShortest(t[i]) + ", " + formatShortest(s[i]) + "]";
    j.setJson("curve", curve + "]");
  }
  return j;
}

// Whether the camera is the opencv model with Brown–Conrady's k1 k2 k3 p1 p2 only, the lens's
// intrinsics and the field limit a `distortion` block gets (its fold, or none): the sidecar
// writes it as `distortion`, as the scenes before issue 36. Found by probing: a user's
// max_field_angle_deg was dropped that way, and the pasted-back block imaged 370 more pixels.
bool plainDistortion(const PhysicalCameraParams& c) {
  const Projection& p = c.projection;
  Projection asDistortion = p;
  asDistortion.maxFieldAngle = Projection{}.maxFieldAngle;
  const bool loaderLimit = p.maxFieldAngle == asDistortion.maxFieldAngle ||
                           p.maxFieldAngle == limitedToFold(asDistortion).maxFieldAngle;
  return c.intrinsicsFromLens && p.model == ProjectionModel::kOpenCv && p.k4 == 0.0 &&
         p.k5 == 0.0 && p.k6 == 0.0 && p.s1 == 0.0 && p.s2 == 0.0 && p.s3 == 0.0 && p.s4 == 0.0 &&
         p.tauX == 0.0 && p.tauY == 0.0 && loaderLimit;
}

// The degrees whose radians (glm::radians, as the scene loader converts) are exactly rad.
std::string exactDegrees(double rad) {
  const double d = glm::degrees(rad);
  double up = d, down = d;
  for (int i = 0; i < 16; ++i, up = std::nextafter(up, 1e9), down = std::nextafter(down, -1e9)) {
    if (glm::radians(up) == rad) return formatShortest(up);
    if (glm::radians(down) == rad) return formatShortest(down);
  }
  return formatShortest(d);
}

// The camera model in the scene's keys: `distortion` {k1 k2 k3 p1 p2} for a plain one, else
// `projection` {model, its coefficients, max_field_angle_deg below 180°, and fx fy cx cy
// when a calibration gave them} (scene_loader_camera.cpp).
JsonObject projectionJson(const PhysicalCameraParams& c) {
  const Projection& p = c.projection;
  JsonObject j;
  if (plainDistortion(c))
    return j.setExact("k1", p.k1)
        .setExact("k2", p.k2)
        .setExact("k3", p.k3)
        .setExact("p1", p.p1)
        .setExact("p2", p.p2);
  j.set("model", std::string(enumName(p.model)));
  if (!c.intrinsicsFromLens)
    j.setExact("fx", p.fx).setExact("fy", p.fy).setExact("cx", p.cx).setExact("cy", p.cy);
  for (const auto& [name, value] : projectionCoefficients(p)) j.setExact(name, value);
  if (p.model != ProjectionModel::kEquirectangular && p.maxFieldAngle < std::numbers::pi)
    j.setJson("max_field_angle_deg", exactDegrees(p.maxFieldAngle));
  return j;
}

// `camera.lens` as the scene writes it: the file, the f-number and focus distance (m from
// the entrance pupil; omitted at infinity) the camera used.
JsonObject lensJson(const LensSpec& spec) {
  JsonObject j;
  j.set("file", spec.prescription.source);
  if (spec.fNumber > 0.0) j.setExact("f_number", spec.fNumber);
  if (spec.focusDistance > 0.0) j.setExact("focus_distance_m", spec.focusDistance);
  return j;
}

// The traced lens's derived data: the sensor distance focusing placed, the camera origin
// (the entrance pupil, lens-space z) and the paraxial data at λ_d (LensSystem::paraxial,
// names with their unit as suffix; a non-finite value, the object at infinity, is null).
JsonObject lensDerivedJson(const LensCamera& lens) {
  JsonObject j;
  j.set("sensor_distance_m", lens.sensorDistance())
      .set("camera_origin", "entrance pupil")
      .setJson("disperses", lens.disperses() ? "true" : "false");  // then λ[0] only is traced
  for (const ParaxialField& f : paraxialFields(lens.paraxial())) {
    const std::string name = std::string(f.name) + (*f.unit ? std::string("_") + f.unit : "");
    if (std::isfinite(f.value))
      j.set(name, f.value);
    else
      j.setJson(name, "null");
  }
  return j;
}

// The camera's scene inputs in the scene's keys and units (docs/scene-format.md), then
// `derived`: what follows from them (SI units, intrinsics). `motion`, `lens_transmittance`
// and `gltf` are not written: a paste-back keeps the scene's own (docs/output.md).
// renderOrigin: the scene's world point the render's positions are relative to (the
// camera's rest position, SceneDescription::renderOrigin); the pose is written in the
// scene file's world.
JsonObject cameraJson(const PhysicalCameraParams& p, const glm::dvec3& renderOrigin,
                      bool hasSensor) {
  const PhysicalCamera camera(p);
  const glm::dvec4 k = camera.intrinsics();
  glm::dmat4 world = p.worldFromCamera;
  world[3] += glm::dvec4(renderOrigin, 0.0);
  std::vector<double> pose;  // row by row
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) pose.push_back(world[c][r]);
  JsonObject j;
  j.setExact("world_from_camera", pose)
      .setExact("resolution", {double(p.resolution.x), double(p.resolution.y)});
  if (!hasSensor)  // with a sensor, the sensor sets them and the scene must not
    j.setJson("sensor_width_mm", millimetres(p.sensorSize.x))
        .setJson("sensor_height_mm", millimetres(p.sensorSize.y))
        .setExact("fill_factor", p.fillFactor);
  if (p.lens) {
    j.set("lens", lensJson(*p.lens));  // the thin lens's keys are refused beside it
  } else {
    j.setJson("focal_length_mm", millimetres(p.focalLength)).setExact("f_number", p.fNumber);
    if (p.focusDistance > 0.0) j.setExact("focus_distance_m", p.focusDistance);
  }
  if (p.aperture)
    j.set("aperture", JsonObject()
                          .setJson("blades", std::to_string(p.aperture->blades))
                          .setExact("rotation_deg", glm::degrees(p.aperture->rotation))
                          .set("pupil", std::string(enumName(p.pupil)))
                          .setJson("diffraction", p.aperture->diffraction ? "true" : "false"));
  if (!p.lens)  // the lens replaces the camera model (the loader refuses both)
    j.set(plainDistortion(p) ? "distortion" : "projection", projectionJson(p));
  j.set("shutter", shutterJson(p.shutter));

  JsonObject d;
  d.set("sensor_size_m", std::vector<double>{p.sensorSize.x, p.sensorSize.y})
      .set("fill_factor", p.fillFactor)
      .set("focal_length_m", p.focalLength);
  // Focus at infinity (focusDistance 0 in PhysicalCameraParams) is null: no distance.
  if (p.focusDistance > 0.0)
    d.set("focus_distance_m", p.focusDistance);
  else
    d.setJson("focus_distance_m", "null");
  // The camera's own aperture: a traced lens has its stop even where the scene gave no
  // camera.aperture (found by probing: "pinhole" for the double-Gauss at f/2).
  const auto& aperture = camera.params().aperture;
  d.set("image_distance_m", camera.imageDistance())
      .set("aperture", !aperture          ? "pinhole"
                       : aperture->blades ? std::to_string(aperture->blades) + " blades"
                                          : "circular")
      .set("working_f_number", camera.workingFNumber())
      .set("shutter_open_s", p.shutter.open())
      .set("shutter_close_s", p.shutter.close())
      .set("exposure_time_s", p.shutter.effectiveTime())
      .set("rolling_shutter_row_time_s", p.shutter.rowTime())
      .set("opencv_fx_fy_cx_cy", std::vector<double>{k.x, k.y, k.z, k.w});
  if (p.projection.model == ProjectionModel::kOpenCv && !camera.lensCamera())
    d.set("opencv_k1_k2_p1_p2_k3",
          std::vector<double>{p.projection.k1, p.projection.k2, p.projection.p1, p.projection.p2,
                              p.projection.k3});
  // The model as cameras.json writes it (camera_export.h): model, coefficients and the
  // field angle where it limits the image.
  if (const LensCamera* lens = camera.lensCamera()) d.set("lens", lensDerivedJson(*lens));
  JsonObject model;
  addCameraModel(model, cameraExport(camera));
  return j.set("derived", d.set("projection", model));
}

// The sensor's scene inputs (the scene's `sensor:` keys), then `derived`: what the capture
// measured or computed from them.
JsonObject sensorJson(const CaptureResult& r) {
  const SensorSettings& sensor = *r.description.sensor;
  std::vector<double> evs, times;
  for (const CaptureFrame& f : r.frames) evs.push_back(f.ev), times.push_back(f.exposureTimeS);
  JsonObject j;
  j.set("model", sensor.spec.name)
      .setExact("iso", sensor.iso)
      .set("noise", std::string(enumName(sensor.noise)))
      .setInteger("noise_seed", sensor.noiseSeed)
      .setInteger("frame", sensor.frame);
  if (const std::optional<AutoExposure>& ae = sensor.autoExposure) {
    JsonObject a;
    a.set("metering", std::string(enumName(ae->metering))).setExact("target", ae->target);
    if (ae->metering == AutoExposure::Metering::kPercentile)
      a.setExact("percentile", ae->percentile);
    j.set("auto_exposure", a);
  }
  if (!sensor.bracketEv.empty()) j.setExact("bracket_ev", sensor.bracketEv);
  JsonObject d;
  d.set("auto_exposure_scale", r.exposureScale)
      .set("frame_ev", evs)
      .set("exposure_times_s", times)
      .set("system_gain_dn_per_e", sensor.spec.systemGain(sensor.iso))
      .set("saturation_e", sensor.spec.saturationElectrons(sensor.iso));
  // Which noise terms this capture drew, and their temporal variance line
  // σ² = slope·(μ − black) + offset at the first frame's time (exposedNoiseTerms).
  const std::vector<std::string> terms = exposedNoiseTerms(sensor.spec, sensor.iso, sensor.noise);
  d.set("noise_terms", terms);
  if (std::find(terms.begin(), terms.end(), "dark_frames") != terms.end())
    d.set("dark_frames", sensor.spec.darkFramesDir.string());
  if (!r.frames.empty()) {
    const ExposureSettings first{r.frames.front().exposureTimeS, sensor.iso};
    if (const auto line = exposedVarianceLine(sensor.spec, first, sensor.noise))
      d.set("noise_variance_slope_dn", line->slopeDn)
          .set("noise_variance_offset_dn2", line->offsetDn2);
  }
  return j.set("derived", d);
}

// The ISP's scene inputs (the scene's `isp:` keys), then `derived`: the gains and matrices
// the development used.
JsonObject ispJson(const CaptureResult& r) {
  const IspSettings& isp = r.description.isp;
  const DevelopedImage& dev = *r.developed;
  JsonObject j;
  j.set("white_balance", std::string(enumName(isp.whiteBalance))).set("illuminant", isp.illuminant);
  if (isp.whiteBalance == IspSettings::WhiteBalance::kRegion)
    j.setExact("region", {double(isp.region.x), double(isp.region.y), double(isp.region.width),
                          double(isp.region.height)});
  j.set("demosaic", std::string(enumName(isp.demosaic)));
  JsonObject d;
  d.set("white_balance_gains", dev.whiteBalance)
      .set("chromatic_adaptation",
           r.description.sensor->spec.cfa.isStacked()
               ? "Bradford from the white's XYZ to D65 (ccm_camera_to_xyz_d65)"
               : "Bradford to D65, in the CCM fit")
      .set("ccm_camera_to_xyz_d65", rowMajor(dev.colorCorrection.cameraToXyz))
      .set("xyz_d65_to_working", rowMajor(dev.colorCorrection.xyzToWorking))
      .set("working_space", "ACEScg");
  return j.set("derived", d);
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
  render.set("spp", double(st.spp))
      .setInteger("seed", desc.render.seed)
      .set("sampler", samplerName(desc.render.sampler))
      .set("max_depth", double(desc.render.maxDepth))
      .set("rr_depth", double(desc.render.rrDepth))
      .set("guiding", desc.render.guiding)
      .set("spectral_control_variate", st.modelled.spectralControlVariate);
  if (!reproducible) render.set("seconds", st.seconds);
  if (st.guide) {  // path guiding's cost (integrator/render/path_guide.h)
    JsonObject guide;
    guide.set("train_spp", double(st.guide->trainSpp))
        .set("iterations", double(st.guide->iterations))
        .set("records", double(st.guide->records))
        .set("leaves", double(st.guide->leaves))
        .set("bytes", double(st.guide->bytes));
    if (!reproducible) guide.set("train_seconds", st.guide->trainSeconds);
    render.set("guide", guide);
  }
  if (desc.render.passes()) {
    JsonObject passes;
    passes.set("first_spp", double(desc.render.spp))
        .set("max_spp", double(desc.render.maxSpp))
        .set("passes", double(st.passes))
        .set("stopped_by", renderStopName(st.stop));
    if (desc.render.targetError) passes.set("target_error", *desc.render.targetError);
    if (desc.render.timeLimitS) passes.set("time_limit_s", *desc.render.timeLimitS);
    render.set("passes", passes);
  }
  if (desc.render.adaptiveThreshold) {
    JsonObject adaptive;
    adaptive
        .set("threshold", *desc.render.adaptiveThreshold)
        // The samples every pixel took (found by probing: an adaptive_min_spp above spp
        // was recorded, though no pixel can take more than spp).
        .set("min_spp",
             double(std::min(desc.render.spp,
                             adaptiveMinSppFor(desc.render.spp, desc.render.adaptiveMinSpp))))
        .set("mean_spp", st.meanSpp);
    render.set("adaptive", adaptive);
  }
  if (st.estimatedError) {
    JsonObject estimate;
    estimate.set("rmse", st.estimatedError->error.rmse)
        .set("mrae", st.estimatedError->error.mrae)
        .set("channel", st.estimatedError->channel)
        .set("method", "two interleaved half-sample images (docs/output.md)");
    render.set("estimated_error", estimate);
  }
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
      .set("camera", cameraJson(desc.camera, desc.renderOrigin, desc.sensor.has_value()));
  if (desc.sensor)
    sidecar.set("sensor", sensorJson(r)).set("isp", ispJson(r));
  else
    sidecar.set("display_exposure", r.displayExposure);
  return sidecar;
}

}  // namespace camsim
