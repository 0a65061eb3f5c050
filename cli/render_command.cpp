#include "cli/render_command.h"

#include <cstdio>
#include <ostream>

#include "cli/format.h"
#include "cli/progress.h"
#include "cli/render_outputs.h"
#include "cli/resource_guard.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/output_set.h"
#include "sensor/io/png_io.h"
#include "sensor/isp/display_image.h"

namespace camsim {
namespace {

struct LoadedScene {
  SceneDescription description;
  std::string text;
};

LoadedScene load(const RenderArgs& args) {
  LoadedScene loaded;
  if (!args.scene) {
    loaded.text = std::string(defaultSceneText());
    loaded.description = loadSceneFromText(loaded.text, "<default: scenes/cornell_box.yaml>", ".");
  } else {
    const std::filesystem::path path(*args.scene);
    loaded.text = readSceneFile(path);
    loaded.description = loadSceneFromText(loaded.text, path.string(), sceneBaseDir(path));
  }
  SceneDescription& d = loaded.description;
  if (args.spp) d.render.spp = *args.spp;
  if (args.seed) d.render.seed = *args.seed;
  if (args.exposureTimeS)
    d.camera.shutter =
        d.camera.shutter.scaled(*args.exposureTimeS / d.camera.shutter.effectiveTime());
  if (args.fNumber) {
    d.camera.fNumber = *args.fNumber;
    if (d.camera.aperture)
      d.camera.aperture.emplace(d.camera.focalLength / d.camera.fNumber,
                                d.camera.aperture->blades(), d.camera.aperture->rotation());
  }
  if ((args.iso || args.noise || args.noiseSeed) && !d.sensor)
    throw UsageError("--iso, --noise and --noise-seed need a scene with a sensor");
  if (args.iso) d.sensor->iso = *args.iso;
  if (args.noiseSeed) d.sensor->noiseSeed = *args.noiseSeed;
  if (args.noise) d.sensor->noise = *args.noise;
  return loaded;
}

// Metadata values: 9 significant digits.
std::string number(double v) {
  return formatNumber(v, 9);
}

void appendCameraMetadata(const PhysicalCamera& camera, Metadata& meta) {
  const PhysicalCameraParams& p = camera.params();
  const glm::dvec4 k = camera.intrinsics();
  meta.insert(meta.end(), {{"camsim:exposure_time_s", number(p.shutter.effectiveTime())},
                           {"camsim:f_number", number(p.fNumber)},
                           {"camsim:focal_length_m", number(p.focalLength)},
                           {"camsim:image_distance_m", number(camera.imageDistance())},
                           {"camsim:pixel_area_m2", number(camera.pixelArea())},
                           {"camsim:opencv_fx_fy_cx_cy", number(k.x) + " " + number(k.y) + " " +
                                                             number(k.z) + " " + number(k.w)},
                           {"camsim:opencv_k1_k2_p1_p2_k3",
                            number(p.distortion.k1) + " " + number(p.distortion.k2) + " " +
                                number(p.distortion.p1) + " " + number(p.distortion.p2) + " " +
                                number(p.distortion.k3)}});
}

// An interrupted render's finished tiles (each has its full spp), as NAME.partial.exr —
// never a final name, so a partial image is not taken for a finished one. Nothing when no
// tile had finished.
std::vector<std::filesystem::path> writePartialExr(const SceneDescription& desc,
                                                   const std::filesystem::path& outDir,
                                                   const Image& xyz, int done, int total,
                                                   std::ostream& log) {
  if (done <= 0) {
    log << "render interrupted before a tile had finished: no output written\n";
    return {};
  }
  const std::string what = std::to_string(done) + " of " + std::to_string(total) + " tiles";
  const Metadata meta = {{"camsim:version", CAMSIM_VERSION},
                         {"camsim:scene", desc.sourceFile},
                         {"camsim:spp", std::to_string(desc.render.spp)},
                         {"camsim:seed", std::to_string(desc.render.seed)},
                         {"camsim:partial", "interrupted after " + what +
                                                " (16x16 px each, all spp); other pixels are 0"}};
  const auto& cs = RgbColorSpace::linearRec709();
  OutputSet outputs(outDir);
  writeExr(outputs.add(desc.name + ".partial.exr"), xyzExrImage(xyz), meta,
           ExrChromaticities{cs.red(), cs.green(), cs.blue(), cs.white()});
  std::vector<std::filesystem::path> files = outputs.commit();
  log << "render interrupted after " << what << ": wrote " << files.front().string()
      << " (unfinished tiles are 0); no final output written\n";
  return files;
}

}  // namespace

std::string fnv1aHex(std::string_view data) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : data) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

RenderCommandResult runRender(const RenderArgs& args, std::ostream& log,
                              const std::atomic<bool>* cancel) {
  LoadedScene loaded = load(args);
  const SceneDescription& desc = loaded.description;
  checkMemoryLimit(desc, args.maxMemoryGb);  // before any work
  const std::filesystem::path outDir(args.outputDir);
  for (const auto& stale : OutputSet::prepareDirectory(outDir))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";

  const PictureSettings picture{args.ocioConfig, {args.display, args.view, args.look}};
  checkPictureSettings(picture);  // a bad config or display/view/look fails before rendering
  const Scene scene(desc);
  loaded.description.releaseDecodedImages();  // the Scene holds its own form of them
  const SpectralResponse response = SpectralResponse::cieXyz();
  std::vector<const SpectralResponse*> responses = {&response};
  std::optional<SpectralResponse> sensorResponse;
  if (desc.sensor) {
    const SensorSpec& spec = desc.sensor->spec;
    const bool mosaic = !spec.cfa.isStacked();
    sensorResponse =
        SpectralResponse::electrons(spec.cfa.channels, spec.qe, mosaic ? &spec.cfa : nullptr);
    responses.push_back(&*sensorResponse);
  }
  ProgressBar progress("rendering " + desc.name);
  RenderOptions options;
  options.spp = desc.render.spp;
  options.seed = desc.render.seed;
  options.threads = args.threads;
  options.cancel = cancel;
  std::atomic<int> tilesDone{0}, tilesTotal{0};
  options.progress = [&](int done, int total) {
    progress.update(done, total);
    tilesDone = done;
    tilesTotal = total;
  };
  const RenderResult result = render(scene, responses, options);
  progress.finish();
  RenderCommandResult outcome;
  if (result.stats.cancelled) {
    outcome.cancelled = true;
    outcome.files = writePartialExr(desc, outDir, result.image, tilesDone, tilesTotal, log);
    return outcome;
  }

  const RenderStats& st = result.stats;
  Metadata meta = {{"camsim:version", CAMSIM_VERSION},
                   {"camsim:scene", desc.sourceFile},
                   {"camsim:scene_fnv1a64", fnv1aHex(loaded.text)},
                   {"camsim:spp", std::to_string(desc.render.spp)},
                   {"camsim:seed", std::to_string(desc.render.seed)},
                   {"camsim:render_seconds", std::to_string(st.seconds)},
                   {"camsim:rejected_samples", std::to_string(st.rejectedSamples)},
                   {"camsim:modelled", st.modelled.describe()},
                   {"camsim:units",
                    "energy on each photosite weighted by the CIE 1931 observer x 683 lm/W: "
                    "XYZ.Y is luminous energy in lm*s (talbot); R,G,B: linear Rec.709 on the "
                    "same scale (1,1,1 has Y = 1 lm*s)"}};
  appendCameraMetadata(scene.camera(), meta);
  OutputSet outputs(outDir);
  // Re-render only for moving scenes, whose motion blur depends on the exposure time.
  auto rerender = [&](double k) {
    SceneDescription longer = desc;
    longer.camera.shutter = desc.camera.shutter.scaled(k);
    const Scene s2(longer);
    RenderOptions o = options;
    o.progress = nullptr;
    return render(s2, *sensorResponse, o).image;
  };
  writeRenderOutputs({desc, scene, result, meta, picture, rerender}, outputs, log);
  outcome.files = outputs.commit();
  const std::filesystem::path stalePartial = outDir / (desc.name + ".partial.exr");
  std::error_code ec;
  if (std::filesystem::remove(stalePartial, ec))
    log << "removed " << stalePartial.string() << " of an interrupted run\n";

  log << "modelled: " << st.modelled.describe() << "\n";
  log << "rendered " << desc.name << ": " << result.image.width << "x" << result.image.height
      << ", " << desc.render.spp << " spp, " << st.threads << " threads, "
      << formatSeconds(st.seconds) << " (" << formatRate(st.samplesPerSecond()) << "samples/s, "
      << formatRate(st.raysPerSecond())
      << "rays/s), rejected samples (NaN/Inf): " << st.rejectedSamples << "\n";
  if (st.rejectedSamples > 0)
    log << "warning: " << st.rejectedSamples << " samples had NaN/Inf radiance and were dropped\n";
  for (const auto& f : outcome.files) log << "wrote " << f.string() << "\n";
  return outcome;
}

}  // namespace camsim
