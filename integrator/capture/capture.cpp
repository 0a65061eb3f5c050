#include "integrator/capture/capture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "integrator/capture/scene_cache.h"
#include "integrator/scene/scene.h"
#include "sensor/base/check.h"
#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"
#include "sensor/io/dark_frame_reader.h"
#include "sensor/model/exposure_control.h"
#include "sensor/model/sensor_model.h"
#include "sensor/spectra/color_space.h"

namespace camsim {
namespace {

// The ISP refuses some settings only on the rendered raw (a region or grey-world white
// balance on a black or fully clipped image): its error is given the scene key
// (isp.white_balance, isp.region; sensor.model for the sensor's own data) and the place the
// scene file sets it, or the enclosing block's, or the file's when defaulted.
[[noreturn]] void rethrowAtIspKey(const SceneDescription& desc, const InputError& e) {
  if (!e.where().file.empty()) throw e;
  using W = IspSettings::WhiteBalance;
  const bool regionKey = desc.isp.whiteBalance == W::kRegion;
  std::string key = "sensor.model";  // the sensor's QE, CFA and levels
  if (e.key() == "white_balance" || (e.key() == "region" && !regionKey))
    key = "isp.white_balance";
  else if (e.key() == "region")
    key = "isp.region";
  else if (e.key().empty())
    key = "isp";
  auto place = desc.keyPlaces.find(key);
  // The sensor's own data (a CFA no demosaicking reads) is its description file's, with the
  // scene's line that named it when there is one (a --sensor override has none).
  if (key == "sensor.model" && desc.sensor && !desc.sensor->spec.sourceFiles.empty()) {
    const InputError own({desc.sensor->spec.sourceName(), 0, 0}, e.key(), e.message());
    if (place == desc.keyPlaces.end()) throw own;
    throw namedBy(own, place->second, key);
  }
  if (place == desc.keyPlaces.end()) place = desc.keyPlaces.find(key.substr(0, key.find('.')));
  const bool fromRaw = key.starts_with("isp.") && desc.isp.whiteBalance != W::kIlluminant;
  throw InputError(
      place != desc.keyPlaces.end() ? place->second : SourceLocation{desc.sourceFile, 0, 0}, key,
      e.message() + (fromRaw ? " (found in the rendered raw)" : ""));
}

Image scaled(const Image& image, double k) {
  Image out = image;
  for (float& v : out.pixels) v = static_cast<float>(static_cast<double>(v) * k);
  return out;
}

// Step 5 for one frame: a mosaic is one plane, a stacked sensor exposes each channel plane
// with its own noise stream.
// With dark frames (the sensor's dark_frames), they replace the signal-independent terms.
std::vector<RawImage> exposeFrame(const Image& electrons, const SensorSettings& sensor,
                                  double exposureTimeS, std::uint64_t frameIndex,
                                  const DarkFrameSet* darkFrames) {
  return exposeChannels(electrons, sensor.spec,
                        ExposureSettings{exposureTimeS, sensor.iso, darkFrames}, sensor.noise,
                        sensor.noiseSeed, frameIndex);
}

double clippedFraction(const std::vector<RawImage>& raws) {
  std::size_t clipped = 0, total = 0;
  for (const RawImage& raw : raws) {
    for (std::uint16_t v : raw.dn) clipped += static_cast<double>(v) >= raw.whiteLevelDn ? 1 : 0;
    total += raw.dn.size();
  }
  return total == 0 ? 0.0 : static_cast<double>(clipped) / static_cast<double>(total);
}

// The one Scene of a capture: step 1's (built here, the caller's cache's or the sequence's)
// is the one step 4 renders again on, at each stretched shutter (Scene::setCamera builds
// only the motion-dependent parts again), so no capture builds a second Scene or reads a
// file twice. A capture whose film was rendered elsewhere (tile parts) builds it at the
// first re-render, from the description.
class CaptureScene {
 public:
  explicit CaptureScene(SceneCache* cache) : cache_(cache) {}
  explicit CaptureScene(Scene& built) : scene_(&built) {}

  // The Scene at description's camera (step 1).
  Scene& at(const SceneDescription& d) {
    if (!scene_) scene_ = cache_ ? &cache_->sceneFor(d) : &built_.emplace(d);
    return *scene_;
  }
  bool reused() const { return cache_ && cache_->reused(); }
  // The Scene at `camera`, a shutter of d's capture, over its exposure window (step 4).
  const Scene& at(const SceneDescription& d, const PhysicalCameraParams& camera) {
    Scene& scene = at(d);
    try {
      scene.setCamera(camera, d, exposureWindow(camera));
    } catch (...) {
      if (cache_) cache_->clear();  // a failed rebuild leaves the Scene unusable
      throw;
    }
    return scene;
  }

 private:
  SceneCache* cache_ = nullptr;
  std::optional<Scene> built_;
  Scene* scene_ = nullptr;
};

// Steps 2–6 on the render's sensor film.
void exposeAndDevelop(CaptureResult& out, const RenderOptions& renderOptions,
                      CaptureScene& scenes) {
  const SceneDescription& desc = out.description;
  const SensorSettings& sensor = *desc.sensor;
  const SensorSpec& spec = sensor.spec;
  const double sceneTime = desc.camera.shutter.effectiveTime();
  const bool moves = out.stats.modelled.time;
  // The film at the scene's exposure stretched by k: rendered again when something moves.
  // A cancelled re-render cancels the capture (its film lacks tiles): no frame is kept.
  const auto filmAt = [&](double k) {
    if (!moves) return scaled(out.sensorFilm, k);
    PhysicalCameraParams longer = desc.camera;
    longer.shutter = desc.camera.shutter.scaled(k);
    const Scene& scene = scenes.at(desc, longer);
    RenderOptions o = renderOptions;
    o.progress = nullptr;
    o.spp = out.stats.spp;  // the samples the first film ended with, in one pass
    o.targetError.reset();
    o.timeLimitS.reset();
    RenderResult again = render(scene, sensorResponse(spec), o);
    out.cancelled = out.cancelled || again.stats.cancelled;
    return std::move(again.image);
  };
  if (sensor.autoExposure) {
    out.exposureScale = autoExposureScale(out.sensorFilm, *sensor.autoExposure,
                                          spec.saturationElectrons(sensor.iso));
    // A video camera's exposure cannot outlast its frame period, the longest bracket's
    // neither (found by probing: 0.22 s metered at 24 fps, over five frame periods, which a
    // shutter given so is refused).
    if (desc.frames) {
      const Shutter& shutter = desc.camera.shutter;
      double most = (1.0 / desc.frames->rateHz) /
                    ((shutter.close() - shutter.open()) * sensor.longestBracketFactor());
      // A 360° shutter's window is the period up to rounding: exactly 1 then, so that the
      // film is not rendered again at an equal shutter (found in review).
      if (std::abs(most - 1.0) < 1e-9) most = 1.0;
      if (out.exposureScale > most) {
        out.exposureScale = most;
        out.exposureAtFramePeriod = true;
      }
    }
  }
  const bool bracketed = !sensor.bracketEv.empty();
  const std::vector<double> evs = bracketed ? sensor.bracketEv : std::vector<double>{0.0};
  const auto zero = std::find(evs.begin(), evs.end(), 0.0);
  out.referenceFrame = zero == evs.end() ? 0 : static_cast<std::size_t>(zero - evs.begin());
  const Image base = out.exposureScale == 1.0 ? out.sensorFilm : filmAt(out.exposureScale);
  if (out.cancelled) return;
  const std::optional<DarkFrameSet> darkFrames = darkFramesFor(spec, sensor.noise);
  for (std::size_t i = 0; i < evs.size(); ++i) {
    CaptureFrame frame;
    frame.ev = evs[i];
    const double k = std::exp2(evs[i]);
    frame.exposureTimeS = sceneTime * out.exposureScale * k;
    frame.frameIndex = sensor.frame + i;
    frame.electrons =
        evs[i] == 0.0 ? base : (moves ? filmAt(out.exposureScale * k) : scaled(base, k));
    if (out.cancelled) {
      out.frames.clear();
      return;
    }
    frame.raws = exposeFrame(frame.electrons, sensor, frame.exposureTimeS, frame.frameIndex,
                             darkFrames ? &*darkFrames : nullptr);
    frame.clippedFraction = clippedFraction(frame.raws);
    try {
      frame.whiteBalanceGains = whiteBalanceGains(frame.raws, spec, desc.isp);
    } catch (const InputError& e) {
      rethrowAtIspKey(desc, e);
    }
    out.frames.push_back(std::move(frame));
  }
  const CaptureFrame& reference = out.frames[out.referenceFrame];
  try {
    out.developed = developRaw(reference.raws, spec, desc.isp, colorCheckerCsvPath(),
                               &reference.whiteBalanceGains);
  } catch (const InputError& e) {
    rethrowAtIspKey(desc, e);
  }
  out.picture = workingRgb(*out.developed);
}

}  // namespace

Image xyzToExposedAcescg(const Image& xyz, double& exposure) {
  double sum = 0.0;
  std::size_t n = 0;
  const int y = xyz.channelIndex("Y");
  for (int j = 0; j < xyz.height; ++j)
    for (int i = 0; i < xyz.width; ++i)
      if (const float v = xyz.at(i, j, y); std::isfinite(v)) sum += static_cast<double>(v), ++n;
  const double mean = n ? sum / static_cast<double>(n) : 0.0;
  exposure = mean > 0.0 ? 0.18 / mean : 1.0;
  return applyColorMatrix(xyz, xyzD65ToWorkingSpace(RgbColorSpace::acesCg()) * exposure,
                          {"R", "G", "B"});
}

namespace {

RenderOptions renderOptionsFor(const SceneDescription& desc, const CaptureOptions& options,
                               CaptureResult& out) {
  RenderOptions o;
  o.spp = desc.render.spp;
  o.seed = desc.render.seed;
  o.targetError = desc.render.targetError;
  o.timeLimitS = desc.render.timeLimitS;
  o.guiding = desc.render.guiding;
  o.maxSpp = std::max(desc.render.maxSpp, desc.render.spp);
  if (desc.render.adaptiveThreshold)
    o.adaptive = AdaptiveSampling{*desc.render.adaptiveThreshold,
                                  adaptiveMinSppFor(desc.render.spp, desc.render.adaptiveMinSpp)};
  o.threads = options.threads;
  o.cancel = options.cancel;
  o.progress = [&out, progress = options.progress](int done, int total) {
    out.tilesDone = done;
    out.tilesTotal = total;
    if (progress) progress(done, total);
  };
  return o;
}

// Step 1 on a built scene, into out (film, sensor film, AOVs, stats).
void renderFilm(const Scene& scene, const RenderOptions& o, CaptureResult& out) {
  const SceneDescription& desc = out.description;
  const SpectralResponse xyz = SpectralResponse::cieXyz();
  std::vector<const SpectralResponse*> responses = {&xyz};
  std::optional<SpectralResponse> electrons;
  if (desc.sensor) responses.push_back(&electrons.emplace(sensorResponse(desc.sensor->spec)));
  RenderResult film = render(scene, responses, o);
  out.stats = film.stats;
  out.cancelled = film.stats.cancelled;
  out.film = std::move(film.images[0]);
  if (desc.sensor) out.sensorFilm = std::move(film.images[1]);
  out.aovs = std::move(film.aovs);
  out.oddHalf = std::move(film.oddHalf);
  out.sampleCounts = std::move(film.sampleCounts);
}

// Steps 2–6 once the film is there; step 4 renders on `scenes`.
void finish(CaptureResult& out, const RenderOptions& o, CaptureScene& scenes) {
  if (out.cancelled) return;
  if (out.description.sensor)
    exposeAndDevelop(out, o, scenes);
  else
    out.picture = xyzToExposedAcescg(out.film, out.displayExposure);
}

// Step 1 on the Scene of `scenes` (built now, or the cache's), which is kept for step 4.
CaptureResult renderFilms(SceneDescription description, const CaptureOptions& options,
                          CaptureScene& scenes) {
  CaptureResult out;
  out.description = std::move(description);
  RenderOptions o = renderOptionsFor(out.description, options, out);
  if (options.tiles) {
    o.tiles = *options.tiles;
    checkTileable(out.description, ModelledDimensions{});  // a sequence: before the scene
  }
  const Scene& scene = scenes.at(out.description);
  out.sceneReused = scenes.reused();
  if (options.tiles) checkTileable(out.description, scene.modelled());
  out.description.releaseDecodedImages();  // the Scene holds its own form of them
  renderFilm(scene, o, out);
  return out;
}

}  // namespace

void checkTileable(const SceneDescription& desc, const ModelledDimensions& modelled) {
  const SourceLocation where{desc.sourceFile, 0, 0};
  if (desc.frames)
    throw InputError(where, "frames",
                     "a frame sequence cannot be split into tiles (--tiles): each frame is a "
                     "capture of its own; render the sequence in one process");
  if (desc.render.passes())
    throw InputError(where, desc.render.targetError ? "render.target_error" : "render.time_limit_s",
                     "a render in passes cannot be split into tiles (--tiles): where it stops "
                     "depends on the whole image's estimated error (or the time); give a fixed "
                     "render.spp instead");
  if (desc.render.adaptiveThreshold)
    throw InputError(where, "render.adaptive_threshold",
                     "an adaptive render cannot be split into tiles (--tiles): its convergence "
                     "checks are scaled by the whole image's mean; render it in one process");
  if (!desc.sensor || !modelled.time) return;
  const SensorSettings& sensor = *desc.sensor;
  const bool bracketMoves = std::any_of(sensor.bracketEv.begin(), sensor.bracketEv.end(),
                                        [](double ev) { return ev != 0.0; });
  if (!sensor.autoExposure && !bracketMoves) return;
  const std::string moving = "something moves during the exposure (" + modelled.describe() +
                             "), so motion blur depends on the exposure time and ";
  if (sensor.autoExposure)
    throw InputError(where, "sensor.auto_exposure",
                     "this capture cannot be split into tiles (--tiles): " + moving +
                         "auto-exposure renders the film again at the exposure time it meters "
                         "on the whole first film; render it in one process, or give a fixed "
                         "exposure time instead of auto_exposure");
  throw InputError(where, "sensor.bracket_ev",
                   "this capture cannot be split into tiles (--tiles): " + moving +
                       "each bracket EV != 0 is rendered again at its own exposure time, a "
                       "film the parts do not carry; render it in one process, or leave the "
                       "brackets out");
}

CaptureResult renderCaptureFilms(SceneDescription description, const CaptureOptions& options) {
  CaptureScene scenes(options.sceneCache);
  return renderFilms(std::move(description), options, scenes);
}

void finishCapture(CaptureResult& out, const CaptureOptions& options) {
  RenderOptions o = renderOptionsFor(out.description, options, out);
  o.progress = nullptr;
  CaptureScene scenes(options.sceneCache);  // built only if step 4 renders again
  finish(out, o, scenes);
}

CaptureResult capture(SceneDescription description, const CaptureOptions& options) {
  CAMSIM_CHECK(!options.tiles);
  CaptureScene scenes(options.sceneCache);
  CaptureResult out = renderFilms(std::move(description), options, scenes);
  RenderOptions o = renderOptionsFor(out.description, options, out);
  o.progress = nullptr;
  finish(out, o, scenes);
  return out;
}

SequenceSummary captureSequence(SceneDescription description, const CaptureOptions& options,
                                const std::function<void(CaptureResult&&, int)>& onFrame) {
  const FrameSequence seq = description.frames.value_or(FrameSequence{});
  description.frames = seq;
  const glm::dvec2 span = sequenceWindow(description);
  Scene scene(description, span);
  description.releaseDecodedImages();
  // Nothing moves anywhere in the sequence: every frame's film is frame 0's (the shutter
  // curve is the same), so it is rendered once; only the sensor's temporal noise differs.
  PhysicalCameraParams whole = description.frameCamera(0);
  whole.shutter = Shutter::box(span.x, span.y);
  scene.setCamera(whole);
  const bool anythingMoves = scene.modelled().time;
  SequenceSummary summary;
  summary.frames = seq.count;
  CaptureResult first;  // when nothing moves: frame 0's render (film, sensor film, AOVs) only
  for (int k = 0; k < seq.count; ++k) {
    CaptureResult out;
    out.description = description;
    out.description.camera = description.frameCamera(k);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%04d", seq.first + k);
    out.description.name += suffix;
    // Bracketed frames take several noise frames each: sequence frame k starts at
    // sensor.frame + k · (brackets or 1).
    if (out.description.sensor)
      out.description.sensor->frame +=
          static_cast<std::uint64_t>(k) *
          std::max<std::uint64_t>(1, out.description.sensor->bracketEv.size());
    const RenderOptions o = renderOptionsFor(out.description, options, out);
    if (k == 0 || anythingMoves) {
      // The motion over the frame's own exposure: steps spread over the whole sequence put a
      // frame between two steps and interpolated its pose across keyframes (found by
      // probing: a ball keyframed to jump 0.2 m between two frames was drawn 0.035 m short
      // of it; a board that jumped 100 m was missing). Keyframed shapes are built again per
      // frame; without keyframes only Embree's time map moves.
      scene.setCamera(out.description.camera, description, exposureWindow(out.description.camera));
      renderFilm(scene, o, out);
      ++summary.rendered;
    } else {
      out.stats = first.stats;
      out.film = first.film;
      out.sensorFilm = first.sensorFilm;
      out.aovs = first.aovs;
      out.sampleCounts = first.sampleCounts;
      out.tilesDone = out.tilesTotal = first.tilesTotal;
    }
    CaptureScene scenes(scene);
    finish(out, o, scenes);  // nothing when cancelled; cancels when a re-render is (step 4)
    if (out.cancelled) {
      summary.cancelled = true;
      onFrame(std::move(out), k);
      return summary;
    }
    if (k == 0 && !anythingMoves) {
      first.stats = out.stats;
      first.film = out.film;
      first.sensorFilm = out.sensorFilm;
      first.aovs = out.aovs;
      first.sampleCounts = out.sampleCounts;
      first.tilesTotal = out.tilesTotal;
    }
    onFrame(std::move(out), k);
  }
  return summary;
}

}  // namespace camsim
