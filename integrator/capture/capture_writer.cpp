#include "integrator/capture/capture_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "integrator/camera/physical_camera.h"
#include "integrator/capture/aov_previews.h"
#include "integrator/capture/bop_writer.h"
#include "integrator/capture/camera_export.h"
#include "integrator/capture/capture_sidecar.h"
#include "integrator/capture/kitti_writer.h"
#include "integrator/render/cryptomatte.h"
#include "integrator/scene/scene_ids.h"
#include "sensor/base/format.h"
#include "sensor/base/luts_directory.h"
#include "sensor/io/dng_writer.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/png_io.h"
#include "sensor/isp/display_image.h"
#include "sensor/spectra/color_space.h"

namespace camsim {
namespace {

// Metadata values: 9 significant digits.
std::string number(double v) {
  return formatNumber(v, 9);
}

ExrChromaticities rec709Chromaticities() {
  const auto& cs = RgbColorSpace::linearRec709();
  return {cs.red(), cs.green(), cs.blue(), cs.white()};
}

Metadata filmMetadata(const CaptureResult& r, bool reproducible) {
  const SceneDescription& desc = r.description;
  const RenderStats& st = r.stats;
  Metadata meta = {{"camsim:version", CAMSIM_VERSION},
                   {"camsim:scene", desc.sourceFile},
                   {"camsim:scene_fnv1a64", desc.sourceFnv1a},
                   {"camsim:spp", std::to_string(st.spp)},
                   {"camsim:seed", std::to_string(desc.render.seed)},
                   {"camsim:rejected_samples", std::to_string(st.rejectedSamples)},
                   {"camsim:modelled", st.modelled.describe()},
                   // 1: nothing moves during the exposure, so the expected electrons scale
                   // with the exposure time (what `camsim expose --exposure-scale` needs).
                   {"camsim:static_scene", st.modelled.time ? "0" : "1"},
                   {"camsim:units",
                    "energy on each photosite weighted by the CIE 1931 observer x 683 lm/W: "
                    "XYZ.Y is luminous energy in lm*s (talbot); R,G,B: linear Rec.709 on the "
                    "same scale (1,1,1 has Y = 1 lm*s)"}};
  if (st.estimatedError)  // the render's estimate of its own error (error_estimate.h)
    meta.insert(meta.end(), {{"camsim:estimated_rmse", number(st.estimatedError->error.rmse)},
                             {"camsim:estimated_mrae", number(st.estimatedError->error.mrae)},
                             {"camsim:estimated_error_channel", st.estimatedError->channel}});
  const PhysicalCamera camera(desc.camera);
  const PhysicalCameraParams& p = camera.params();
  const glm::dvec4 k = camera.intrinsics();
  meta.insert(meta.end(), {{"camsim:exposure_time_s", number(p.shutter.effectiveTime())},
                           {"camsim:f_number", number(p.fNumber)},
                           {"camsim:focal_length_m", number(p.focalLength)},
                           {"camsim:image_distance_m", number(camera.imageDistance())},
                           {"camsim:pixel_area_m2", number(camera.pixelArea())},
                           {"camsim:opencv_fx_fy_cx_cy", number(k.x) + " " + number(k.y) + " " +
                                                             number(k.z) + " " + number(k.w)}});
  // The camera model as cameras.json names it, its coefficients in OpenCV's order
  // (camera_export.h); the five Brown–Conrady numbers as before for the opencv model.
  const CameraExport model = cameraExport(camera);
  meta.push_back({"camsim:camera_model", model.model});
  if (const std::string c = cameraModelText(model); !c.empty())
    meta.push_back({"camsim:camera_model_coefficients", c});
  if (p.projection.model == ProjectionModel::kOpenCv && !model.tracedLens)
    meta.push_back({"camsim:opencv_k1_k2_p1_p2_k3",
                    number(p.projection.k1) + " " + number(p.projection.k2) + " " +
                        number(p.projection.p1) + " " + number(p.projection.p2) + " " +
                        number(p.projection.k3)});
  // A traced lens: its file, sensor distance and paraxial data at λ_d (camsim:lens_<name>_<unit>;
  // the object distance at infinity is "inf").
  if (const LensCamera* lens = camera.lensCamera()) {
    meta.push_back({"camsim:lens_file", p.lens->prescription.source});
    meta.push_back({"camsim:lens_sensor_distance_m", number(lens->sensorDistance())});
    for (const ParaxialField& f : paraxialFields(lens->paraxial()))
      meta.push_back(
          {std::string("camsim:lens_") + f.name + (*f.unit ? std::string("_") + f.unit : ""),
           std::isfinite(f.value) ? number(f.value) : "inf"});
  }
  if (!reproducible) meta.push_back({"camsim:render_seconds", std::to_string(st.seconds)});
  return meta;
}

std::string frameStem(const CaptureResult& r, std::size_t i) {
  if (r.description.sensor->bracketEv.empty()) return r.description.name;
  return r.description.name + bracketSuffix(r.frames[i].ev);
}

// NAME[_evX].dng and NAME[_evX]_raw.exr per frame (a stacked sensor: a raw EXR per plane).
void writeFrames(const CaptureResult& r, const Metadata& meta, OutputSet& outputs) {
  const SceneDescription& desc = r.description;
  const SensorSettings& sensor = *desc.sensor;
  const SensorSpec& spec = sensor.spec;
  // The DNG's colour follows the ISP's white balance: matrices for its illuminant (and
  // D65), AsShotNeutral from the gains it applies to each frame.
  DngColor color = spec.qe.size() == 3 && !spec.cfa.isStacked()
                       ? dngColorFromQe(spec.qe, desc.isp.illuminant, colorCheckerCsvPath())
                       : DngColor{};
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    const CaptureFrame& frame = r.frames[i];
    Metadata frameMeta = meta;
    // The frame's own exposure time (a bracket's, auto-exposure's) in place of the scene's,
    // both in shortest round-trip form: camsim expose reads them back (found by
    // probing: written with %f, 12.3 µs became 0.000012 and 0.4 µs became 0, so the
    // re-exposure's dark signal and EXIF ExposureTime were wrong; an ISO of 1e-300 became 0).
    for (auto& [key, value] : frameMeta)
      if (key == "camsim:units")
        value =
            "raw.DN: raw digital numbers as the ADC gives them, black level "
            "included; electrons.<channel>: the noise-free expected photo-electrons per "
            "photosite at this frame's exposure";
      else if (key == "camsim:exposure_time_s")
        value = formatShortest(frame.exposureTimeS);
    frameMeta.insert(frameMeta.end(), {{"camsim:sensor", spec.name},
                                       {"camsim:sensor_source", spec.sourceKind()},
                                       {"camsim:iso", formatShortest(sensor.iso)},
                                       {"camsim:noise_seed", std::to_string(sensor.noiseSeed)},
                                       {"camsim:frame", std::to_string(frame.frameIndex)}});
    const std::string stem = frameStem(r, i);
    if (spec.cfa.isStacked()) {
      for (std::size_t c = 0; c < frame.raws.size(); ++c)
        writeRawExr(outputs.add(stem + "_raw_" + spec.cfa.channels[c] + ".exr"), frame.raws[c],
                    frame.electrons.channel(static_cast<int>(c)), frameMeta);
      continue;
    }
    if (spec.qe.size() == 3) color.asShotNeutral = dngNeutralFromGains(frame.whiteBalanceGains);
    DngCapture dng;
    dng.fNumber = desc.camera.fNumber;
    dng.focalLengthMm = desc.camera.focalLength * 1e3;
    dng.dateTimeOriginal = "2000:01:01 00:00:00";  // fixed: same scene, same bytes
    dng.exposureTimeS = frame.exposureTimeS;
    dng.iso = sensor.iso;
    // A bracket's offset as cameras record auto-exposure bracketing; BaselineExposure 0:
    // the ISP develops the normalised raw × 1 (dng_writer.h).
    if (!sensor.bracketEv.empty()) dng.exposureBiasEv = frame.ev;
    dng.noiseProfile =
        dngNoiseProfile(spec, ExposureSettings{frame.exposureTimeS, sensor.iso}, sensor.noise);
    writeDng(outputs.add(stem + ".dng"), frame.raws.front(), color, frameMeta, dng);
    writeRawExr(outputs.add(stem + "_raw.exr"), frame.raws.front(), frame.electrons, frameMeta);
  }
}

// An interrupted capture's finished tiles (each has its full spp) as NAME.partial.exr —
// never a final name, so a partial image is not taken for a finished one.
WrittenCapture writePartial(const CaptureResult& r, const std::filesystem::path& dir) {
  if (r.tilesDone <= 0) return {};
  const SceneDescription& desc = r.description;
  const std::string what =
      std::to_string(r.tilesDone) + " of " + std::to_string(r.tilesTotal) + " tiles";
  const Metadata meta = {{"camsim:version", CAMSIM_VERSION},
                         {"camsim:scene", desc.sourceFile},
                         {"camsim:spp", std::to_string(desc.render.spp)},
                         {"camsim:seed", std::to_string(desc.render.seed)},
                         {"camsim:partial", "interrupted after " + what +
                                                " (16x16 px each, all spp); other pixels are 0"}};
  OutputSet outputs(dir);
  writeExr(outputs.add(desc.name + ".partial.exr"), xyzExrImage(r.film), meta,
           rec709Chromaticities());
  return {outputs.commit(), {}};
}

// The image's channels followed by the ground-truth layers (none when aovs is empty).
Image withLayers(const Image& image, const Image& aovs) {
  if (aovs.pixels.empty()) return image;
  std::vector<std::string> channels = image.channels;
  channels.insert(channels.end(), aovs.channels.begin(), aovs.channels.end());
  Image out(image.width, image.height, channels);
  const std::size_t a = image.channels.size(), b = aovs.channels.size();
  for (std::size_t p = 0; p < static_cast<std::size_t>(image.width * image.height); ++p) {
    for (std::size_t c = 0; c < a; ++c) out.pixels[p * (a + b) + c] = image.pixels[p * a + c];
    for (std::size_t c = 0; c < b; ++c) out.pixels[p * (a + b) + a + c] = aovs.pixels[p * b + c];
  }
  return out;
}

// The Cryptomatte header attributes of the scene's id aovs (cryptomatte.h) after meta.
Metadata withCryptomatte(Metadata meta, const SceneDescription& desc) {
  const SceneIds ids = sceneIds(desc);
  for (IdKind k : idKindsOf(desc.render.aovs)) {
    const Metadata m = cryptomatteMetadata(cryptomatteTypeName(k), ids[k].names);
    meta.insert(meta.end(), m.begin(), m.end());
  }
  return meta;
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

std::string captureFrameFile(const CaptureResult& result, std::size_t frame) {
  const bool stacked = result.description.sensor->spec.cfa.isStacked();
  return frameStem(result, frame) +
         (stacked ? "_raw_" + result.description.sensor->spec.cfa.channels.back() + ".exr"
                  : ".dng");
}

WrittenCapture writeCapture(const CaptureResult& result, const CaptureOutputOptions& options,
                            const PoseModels* models) {
  if (result.cancelled) return writePartial(result, options.directory);
  const SceneDescription& desc = result.description;
  // Before any file: the models must be writable (a merge's parts).
  std::optional<PoseModels> made;
  if (!models) models = &made.emplace(desc);
  const Metadata meta = filmMetadata(result, options.reproducible);
  OutputSet outputs(options.directory);
  writeExr(outputs.add(desc.name + ".exr"),
           withLayers(withLayers(xyzExrImage(result.film), result.aovs), result.sampleCounts),
           withCryptomatte(meta, desc), rec709Chromaticities());
  if (options.aovPreviews && !result.aovs.pixels.empty())
    for (const AovPreview& p : aovPreviews(result.aovs))
      writePng8(outputs.add(desc.name + "_" + p.suffix + ".png"), p.width, p.height, p.rgb, p.srgb);
  JsonObject sidecar = captureSidecar(result, options.reproducible);
  if (desc.sensor) writeFrames(result, meta, outputs);
  sidecar.set("color", writePicture(result.picture, desc.name, options.picture,
                                    desc.sensor.has_value(), meta, outputs));
  outputs.addText(desc.name + ".json", sidecar.str() + "\n");
  WrittenCapture written;
  written.files = outputs.commit();
  const std::filesystem::path stalePartial = options.directory / (desc.name + ".partial.exr");
  std::error_code ec;
  if (std::filesystem::remove(stalePartial, ec)) written.removed.push_back(stalePartial);
  // The BOP layout after NAME.png, which it copies (a sequence's: CaptureRunWriter).
  if (desc.exportsTo(ExportFormat::kBop) && !desc.frames)
    for (auto& f :
         writeBop(result, *models, options.directory, options.datasetItem, &written.skipped))
      written.files.push_back(std::move(f));
  if (desc.exportsTo(ExportFormat::kKitti) && !desc.frames)
    for (auto& f : writeKittiFrame(result, models->ownOfShape(), options.directory,
                                   options.datasetItem, &written.skipped))
      written.files.push_back(std::move(f));
  return written;
}

}  // namespace camsim
