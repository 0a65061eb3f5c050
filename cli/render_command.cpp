// `camsim render`: parse → capture (the library call) → write → print.
#include "cli/render_command.h"

#include <atomic>
#include <optional>
#include <ostream>

#include "integrator/capture/bop_writer.h"
#include "integrator/capture/capture_run.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/capture/default_scene.h"
#include "integrator/capture/progress.h"
#include "integrator/capture/resource_guard.h"
#include "integrator/capture/tile_parts.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/io/output_set.h"
#include "sensor/model/exposure_control.h"

namespace camsim {
namespace {

void printInterrupted(const CaptureResult& r, const WrittenCapture& written, std::ostream& log) {
  const std::string what =
      std::to_string(r.tilesDone) + " of " + std::to_string(r.tilesTotal) + " tiles";
  if (written.files.empty())
    log << "render interrupted before a tile had finished: no output written\n";
  else
    log << "render interrupted after " << what << ": wrote " << written.files.front().string()
        << " (unfinished tiles are 0); no final output written\n";
}

void printRendered(const CaptureResult& r, std::ostream& log) {
  const RenderStats& st = r.stats;
  log << "modelled: " << st.modelled.describe() << "\n";
  log << "rendered " << r.description.name << ": " << r.film.width << "x" << r.film.height << ", "
      << st.spp << " spp, " << st.threads << " threads, " << formatSeconds(st.seconds) << " ("
      << formatRate(st.samplesPerSecond()) << "samples/s, " << formatRate(st.raysPerSecond())
      << "rays/s), rejected samples (NaN/Inf): " << st.rejectedSamples << "\n";
  if (r.description.render.adaptiveThreshold)
    log << "adaptive sampling: threshold "
        << formatNumber(*r.description.render.adaptiveThreshold, 3) << ", "
        << formatNumber(st.meanSpp, 3) << " spp on average (at most " << st.spp << ")\n";
  if (r.description.render.passes())
    log << "passes: " << st.passes << ", stopped by " << renderStopName(st.stop) << " at " << st.spp
        << " spp\n";
  if (st.estimatedError)
    log << "estimated error (" << st.estimatedError->channel << ", two half-sample images): rMSE "
        << formatNumber(st.estimatedError->error.rmse, 3) << ", MRAE "
        << formatNumber(st.estimatedError->error.mrae, 3) << "\n";
  if (st.rejectedSamples > 0)
    log << "warning: " << st.rejectedSamples << " samples had NaN/Inf radiance and were dropped\n";
}

// --tiles k/M: share k of the tiles' films as DIR/NAME.part-k-of-M.exr, nothing else.
RenderCommandResult runTilePart(SceneDescription desc, const RenderArgs& args,
                                CaptureOptions options, std::ostream& log) {
  const Share share = *args.tiles;
  options.tiles = share;
  checkPoseExports(desc);  // the merge writes the layout: refuse before rendering, as a render
  const std::string what = "part " + std::to_string(share.index) + " of " +
                           std::to_string(share.count) + " of " + desc.name;
  ProgressBar progress("rendering " + what);
  options.progress = [&](int done, int total) { progress.update(done, total); };
  const CaptureResult r = renderCaptureFilms(std::move(desc), options);
  progress.finish();
  if (r.cancelled) {
    log << "render interrupted after " << r.tilesDone << " of " << r.tilesTotal << " tiles of "
        << what << ": no part written\n";
    return {{}, true};
  }
  const std::filesystem::path file =
      writeTilePart(r, share, {args.outputDir, args.overrides, args.reproducible});
  const RenderStats& st = r.stats;
  log << "modelled: " << st.modelled.describe() << "\n";
  log << "rendered " << what << ": "
      << share.itemsOf(renderTileCount({r.film.width, r.film.height})) << " of "
      << renderTileCount({r.film.width, r.film.height}) << " tiles of " << r.film.width << "x"
      << r.film.height << ", " << r.description.render.spp << " spp, " << st.threads << " threads, "
      << formatSeconds(st.seconds) << ", rejected samples (NaN/Inf): " << st.rejectedSamples
      << "\n";
  log << "wrote " << file.string() << " (camsim merge assembles the " << share.count << " parts)\n";
  return {{file}, false};
}

}  // namespace

SceneDescription loadRenderScene(const RenderArgs& args) {
  SceneDescription d;
  if (!args.scene) {
    d = loadSceneFromText(std::string(defaultSceneText()), std::string(kDefaultSceneName), ".");
  } else {
    const std::filesystem::path path(*args.scene);
    d = loadSceneFromText(readSceneFile(path), path.string(), sceneBaseDir(path));
  }
  const SourceLocation commandLine{"<command line>", 0, 0};
  try {
    applyOverrides(d, args.overrides, commandLine);
  } catch (const InputError& e) {
    throw namedByOverride(e, args.overrides, commandLine, overrideFlag);  // "--iso", not sensor.iso
  }
  return d;
}

void printCaptureNotes(const CaptureResult& r, std::ostream& log) {
  const SceneDescription& desc = r.description;
  if (desc.sensor && desc.sensor->autoExposure) {
    const AutoExposure& ae = *desc.sensor->autoExposure;
    log << "auto-exposure (" << meteringName(ae.metering) << ", target " << ae.target
        << " of saturation): exposure time "
        << desc.camera.shutter.effectiveTime() * r.exposureScale << " s (x" << r.exposureScale
        << " the scene's"
        << (r.exposureAtFramePeriod ? ", held to the frame period 1/frames.rate_hz" : "")
        << "), ISO " << desc.sensor->iso << "\n";
  }
  for (std::size_t i = 0; i < r.frames.size(); ++i)
    if (r.frames[i].clippedFraction > 0.01)
      log << "note: " << captureFrameFile(r, i) << ": " << 100.0 * r.frames[i].clippedFraction
          << " % of photosites clipped\n";
}

namespace {

RenderCommandResult renderScene(SceneDescription desc, const RenderArgs& args, std::ostream& log,
                                const std::atomic<bool>* cancel) {
  for (const std::string& note : desc.notes) log << "note: " << note << "\n";  // import notes
  checkMemoryLimit(desc, args.maxMemoryGb);                                    // before any work
  CaptureOutputOptions out{
      args.outputDir, {args.ocioConfig, {args.display, args.view, args.look}}, args.aovPreviews};
  out.reproducible = args.reproducible;
  CaptureOptions options;
  options.threads = args.threads;
  options.cancel = cancel;
  if (args.tiles && desc.frames) checkTileable(desc, ModelledDimensions{});  // before any file
  // An error from here on leaves no empty folder; tile parts share theirs with other jobs.
  std::optional<NewDirectoryCleanup> cleanup;
  if (!args.tiles) cleanup.emplace(out.directory);
  for (const auto& stale : OutputSet::prepareDirectory(out.directory))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";
  if (args.tiles) return runTilePart(std::move(desc), args, options, log);
  checkPictureSettings(out.picture);  // a bad config or display/view/look fails before rendering

  // One frame or a sequence (captureScene): each frame written (atomically; a sequence's
  // as NAME_NNNN.*) as soon as it is captured, a sequence's camera exports at the end.
  const bool sequence = desc.frames.has_value();
  const int count = sequence ? desc.frames->count : 1;
  ProgressBar progress("rendering " + desc.name +
                       (sequence ? " (" + std::to_string(count) + " frames)" : ""));
  options.progress = [&](int done, int total) { progress.update(done, total); };
  CaptureRunWriter writer(out, desc);  // the pose exports' models: a bad scene fails here
  SequenceSummary summary;
  try {
    summary = captureScene(std::move(desc), options, [&](CaptureResult&& r, int) {
      printCaptureNotes(r, log);
      const WrittenCapture written = writer.write(r);
      if (r.cancelled) return printInterrupted(r, written, log);
      for (const auto& f : written.removed)
        log << "removed " << f.string() << " of an interrupted run\n";
      if (!sequence) printRendered(r, log);
    });
  } catch (const InputError&) {
    writer.discard();  // bad input: nothing written (a sequence's earlier frames)
    throw;
  }
  progress.finish();
  writer.finish();
  RenderCommandResult outcome{writer.files(), summary.cancelled};
  if (summary.cancelled) return outcome;
  if (sequence)
    log << "sequence: " << summary.frames << " frames, " << summary.rendered
        << (summary.rendered == summary.frames
                ? " rendered"
                : " rendered (nothing moves: the others reuse its film)")
        << "\n";
  for (const auto& f : outcome.files) log << "wrote " << f.string() << "\n";
  for (const std::string& s : writer.skippedExports()) log << s << "\n";
  return outcome;
}

}  // namespace

RenderCommandResult runRender(const RenderArgs& args, std::ostream& log,
                              const std::atomic<bool>* cancel) {
  SceneDescription desc = loadRenderScene(args);  // the scene file's own errors as they are
  try {
    return renderScene(std::move(desc), args, log, cancel);
  } catch (const InputError& e) {
    // A value a flag gave (--target-error with --tiles) is refused by the flag's name.
    throw namedByOverride(e, args.overrides, {"<command line>", 0, 0}, overrideFlag);
  }
}

}  // namespace camsim
