#include "cli/render_outputs.h"

#include <ostream>

#include "cli/json_writer.h"
#include "cli/sensor_outputs.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/io/exr_io.h"
#include "sensor/isp/display_image.h"
#include "sensor/isp/isp_pipeline.h"
#include "sensor/spectra/color_space.h"

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
      .set("f_number", p.fNumber)
      .set("focus_distance_m", p.focusDistance)
      .set("image_distance_m", camera.imageDistance())
      .set("aperture",
           p.aperture ? (p.aperture->blades() ? std::to_string(p.aperture->blades()) + " blades"
                                              : "circular")
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

}  // namespace

Image xyzExrImage(const Image& xyz) {
  const Image rgb = xyzToRgb(xyz, RgbColorSpace::linearRec709());
  Image out(xyz.width, xyz.height, {"R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z"});
  for (int y = 0; y < xyz.height; ++y)
    for (int x = 0; x < xyz.width; ++x)
      for (int c = 0; c < 3; ++c) {
        out.at(x, y, c) = rgb.at(x, y, c);
        out.at(x, y, 3 + c) = xyz.at(x, y, c);
      }
  return out;
}

void writeRenderOutputs(const RenderOutputInputs& in, OutputSet& outputs, std::ostream& log) {
  const SceneDescription& desc = in.description;
  const RenderStats& st = in.result.stats;
  const auto& rec709 = RgbColorSpace::linearRec709();
  writeExr(outputs.add(desc.name + ".exr"), xyzExrImage(in.result.image), in.metadata,
           ExrChromaticities{rec709.red(), rec709.green(), rec709.blue(), rec709.white()});

  std::vector<std::string> inputFiles;
  for (const auto& f : desc.inputFiles) inputFiles.push_back(f.string());
  JsonObject sidecar;
  sidecar.set("camsim_version", CAMSIM_VERSION)
      .set("scene", desc.sourceFile)
      .set("input_files", inputFiles)
      .set("render", JsonObject()
                         .set("spp", double(desc.render.spp))
                         .set("seed", double(desc.render.seed))
                         .set("sampler", samplerName(desc.render.sampler))
                         .set("max_depth", double(desc.render.maxDepth))
                         .set("seconds", st.seconds)
                         .set("rejected_samples", double(st.rejectedSamples))
                         .set("modelled", st.modelled.describe()))
      .set("camera", cameraJson(in.scene.camera()));

  if (desc.sensor) {
    const SensorSettings& sensor = *desc.sensor;
    DngCapture capture;
    capture.fNumber = desc.camera.fNumber;
    capture.focalLengthMm = desc.camera.focalLength * 1e3;
    capture.dateTimeOriginal = "2000:01:01 00:00:00";  // fixed: same scene, same bytes
    const SensorOutputs frames = writeSensorFrames(
        sensor, desc.isp, capture, desc.name, desc.camera.shutter.effectiveTime(), st.modelled.time,
        in.result.images[1], in.rerender, in.metadata, outputs, log);
    for (const auto& f : frames.frames)
      if (f.clippedFraction > 0.01)
        log << "note: " << (f.dngFile.empty() ? f.rawExrFile : f.dngFile) << ": "
            << 100.0 * f.clippedFraction << " % of photosites clipped\n";
    const DevelopedImage dev =
        developRaw(frames.referenceRaws, sensor.spec, desc.isp,
                   lutsDirectory() / "spectra" / "colorchecker_classic_reflectance.csv");
    Image working = dev.working;
    if (working.channelCount() == 1) {  // monochrome: grey RGB
      Image grey(working.width, working.height, {"R", "G", "B"});
      for (size_t p = 0; p < working.pixels.size(); ++p)
        for (size_t c = 0; c < 3; ++c) grey.pixels[p * 3 + c] = working.pixels[p];
      working = grey;
    }
    std::vector<double> evs, times;
    for (const auto& f : frames.frames) evs.push_back(f.ev), times.push_back(f.exposureTimeS);
    JsonObject sensorJson;
    sensorJson.set("model", sensor.spec.name)
        .set("iso", sensor.iso)
        .set("noise", noiseModeName(sensor.noise))
        .set("noise_seed", double(sensor.noiseSeed))
        .set("frame", double(sensor.frame))
        .set("auto_exposure",
             sensor.autoExposure ? meteringName(sensor.autoExposure->metering) : "off")
        .set("auto_exposure_scale", frames.exposureScale)
        .set("bracket_ev", evs)
        .set("exposure_times_s", times)
        .set("system_gain_dn_per_e", sensor.spec.systemGain(sensor.iso))
        .set("saturation_e", sensor.spec.saturationElectrons(sensor.iso));
    sidecar.set("sensor", sensorJson);
    const char* wb[] = {"illuminant", "region", "grey_world"};
    sidecar.set("isp",
                JsonObject()
                    .set("white_balance", wb[static_cast<int>(desc.isp.whiteBalance)])
                    .set("illuminant", desc.isp.illuminant)
                    .set("white_balance_gains", dev.whiteBalance)
                    .set("chromatic_adaptation",
                         sensor.spec.cfa.isStacked()
                             ? "Bradford from the white's XYZ to D65 (ccm_camera_to_xyz_d65)"
                             : "Bradford to D65, in the CCM fit")
                    .set("demosaic", desc.isp.demosaic == DemosaicMethod::kMalvarHeCutler
                                         ? "malvar-he-cutler"
                                         : "bilinear")
                    .set("ccm_camera_to_xyz_d65", matrixRows(dev.colorCorrection.cameraToXyz))
                    .set("xyz_d65_to_working", matrixRows(dev.colorCorrection.xyzToWorking))
                    .set("working_space", "ACEScg"));
    sidecar.set("color", writePicture(working, desc.name, in.picture, true, in.metadata, outputs));
  } else {
    double exposure = 1.0;
    const Image acescg = xyzToExposedAcescg(in.result.image, exposure);
    sidecar.set("display_exposure", exposure);
    sidecar.set("color", writePicture(acescg, desc.name, in.picture, false, in.metadata, outputs));
  }
  outputs.addText(desc.name + ".json", sidecar.str() + "\n");
}

}  // namespace camsim
