// capture(): the capture sequence as one library call, from a loaded scene to everything a
// capture produces, writing nothing (capture_writer.h writes it). Every front end (the
// CLI, the Python module) calls it; its steps, as ISETCam's sensorCompute lists them:
//
//   1. render       the spectral film: CIE XYZ (absolute, lm·s per photosite) and, with a
//                   sensor, the noise-free expected electrons at the scene's exposure
//   2. meter        auto-exposure on the noise-free electrons (sensor/model/exposure_control.h):
//                   a factor k on the exposure time, ISO kept
//   3. bracket      one frame per bracket EV (or one at 0 EV), at T·k·2^EV
//   4. re-render    only when something moves during the exposure (motion blur depends on
//                   the exposure time): the film again with the shutter stretched, on step
//                   1's Scene (its shapes and BVH rebuilt over the stretched exposure window
//                   when something has keyframed motion; no file read again); a static
//                   scene's electrons scale linearly
//   5. expose       photons → electrons → noise → ADC per frame (sensor::expose), noise from
//                   sensor.noiseSeed, frame index sensor.frame + bracket index; a stacked
//                   sensor exposes each channel plane with its own stream
//   6. develop      the reference frame (0 EV, else the first) through the ISP
//                   (isp_pipeline.h) to scene-linear ACEScg
// Without a sensor, step 6 is XYZ → ACEScg with the mean luminance exposed to 0.18.
//
// capture() is renderCaptureFilms() (step 1) then finishCapture() (steps 2–6), so that the
// later steps can run on films rendered elsewhere: one frame split across processes as
// tile shares (Share, sensor/base/share.h; camsim render --tiles, assembled by camsim merge:
// tile_parts.h). Step 1 is per pixel (film, sensor film and every AOV channel, ID mattes
// included, depend on the pixel's own samples only), steps 2–6 need the whole image. A
// capture that renders again in step 4 — something moves during the exposure and
// auto-exposure or a bracket changes the exposure time — needs the whole film before it
// can render, so it cannot be tiled (checkTileable); nor can a frame sequence.
//
// | option     | unit | default | meaning |
// |------------|------|---------|---------|
// | threads    | —    | 0       | 0: all hardware threads; the result is the same for any count |
// | progress   | —    | none    | (tiles done, tiles total) of the main render, from worker threads |
// | cancel     | —    | none    | checked every 64 samples of a pixel; a cancelled capture has only the finished tiles (a cancelled re-render in step 4 cancels the capture too) |
// | tiles      | —    | none    | renderCaptureFilms only: render this share of the tiles (render.h) |
// | sceneCache | —    | none    | the caller's SceneCache: step 1 renders on the Scene built by an earlier capture when only the camera, spp, seed, sensor or ISP changed (scene_cache.h; same bytes), and step 4 on the same Scene; none: built here, once per capture |
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "integrator/render/render.h"
#include "integrator/scene/scene_description.h"
#include "sensor/base/image.h"
#include "sensor/isp/isp_pipeline.h"
#include "sensor/model/raw_image.h"

namespace camsim {

class SceneCache;  // scene_cache.h

struct CaptureOptions {
  int threads = 0;
  std::function<void(int, int)> progress;
  const std::atomic<bool>* cancel = nullptr;
  std::optional<Share> tiles;
  // Not used by captureSequence (it builds one Scene for all its frames and brackets, moved
  // to each frame's exposure).
  SceneCache* sceneCache = nullptr;
};

struct CaptureFrame {
  double ev = 0.0;               // bracket offset (0 without brackets)
  double exposureTimeS = 0.0;    // effective exposure time T·k·2^EV (s)
  std::uint64_t frameIndex = 0;  // the noise stream's frame: sensor.frame + bracket index
  Image electrons;               // expected e⁻ per photosite at this exposure, noise-free
  std::vector<RawImage> raws;    // mosaic: one; stacked: one per channel plane
  // The white-balance gains the ISP applies to this frame (one per camera channel; the
  // reference channel G or Y is 1): a raw converter's AsShotNeutral is 1/g.
  std::vector<double> whiteBalanceGains;
  double clippedFraction = 0.0;  // photosites at the white level
};

struct CaptureResult {
  SceneDescription description;  // what was captured (decoded texels released)
  RenderStats stats;             // of the main render
  // Cancelled: only tiles that finished hold values (others are 0) and nothing after the
  // render ran (no frames, no picture).
  bool cancelled = false;
  int tilesDone = 0, tilesTotal = 0;
  bool sceneReused = false;  // step 1 rendered on options.sceneCache's Scene, not a new one
  Image film;                // CIE XYZ: energy × 683 lm/W per photosite (Y in lm·s), absolute
  Image sensorFilm;    // with a sensor: expected e⁻ at the scene's exposure time; else empty
  Image aovs;          // the ground truth render.aovs asks for (aov_film.h); else empty
  Image oddHalf;       // RenderResult::oddHalf: for a tile part's error estimate at the merge
  Image sampleCounts;  // adaptive sampling: each pixel's samples (channel "spp"); else empty

  double exposureScale = 1.0;               // auto-exposure's factor on every frame's exposure time
  bool exposureAtFramePeriod = false;       // a sequence's auto-exposure held to its frame period
  std::vector<CaptureFrame> frames;         // with a sensor: one per bracket, in the scene's order
  std::size_t referenceFrame = 0;           // the frame developed (0 EV, else the first)
  std::optional<DevelopedImage> developed;  // with a sensor

  // Scene-linear ACEScg (R, G, B; 0.18 = mid-grey): the developed image (a monochrome
  // sensor's plane as grey RGB), or without a sensor the exposed XYZ film.
  Image picture;
  double displayExposure = 1.0;  // without a sensor: the factor on XYZ (0.18 / mean Y)
};

// One Scene per capture: step 4 renders again on step 1's Scene, never reading a file twice.
// Throws InputError for inputs only the capture discovers (a white balance the rendered raw
// refuses; a moving shape that reaches too far over a stretched shutter).
// options.tiles must be empty (a share is finished only once its film is whole).
CaptureResult capture(SceneDescription description, const CaptureOptions& options = {});

// Step 1 alone: description (decoded texels released), stats, film, sensor film, AOVs and
// the tile counts; nothing after the render ran. With options.tiles only that share's
// tiles hold values (the others are 0), the stats count its samples, and a scene that
// cannot be tiled is an InputError (checkTileable) before any rendering.
CaptureResult renderCaptureFilms(SceneDescription description, const CaptureOptions& options = {});
// Steps 2–6 on result.film, sensorFilm and stats.modelled (nothing when result.cancelled):
// fills exposureScale, frames, referenceFrame, developed, picture, displayExposure. A
// re-render (step 4) renders the whole image on options.sceneCache's Scene, else on one
// built from result.description at the first re-render and kept for the others.
void finishCapture(CaptureResult& result, const CaptureOptions& options = {});

// InputError (naming the scene file and the key) when a capture of `description`, which
// integrates `modelled`, cannot be split into tile shares: a frame sequence (`frames`), or
// a re-render after metering (step 4: modelled.time with auto-exposure or a bracket EV ≠ 0).
void checkTileable(const SceneDescription& description, const ModelledDimensions& modelled);

struct SequenceSummary {
  int frames = 0;    // handed to onFrame
  int rendered = 0;  // of them rendered; the others reuse frame 0's film (nothing moves)
  bool cancelled = false;
};

// A frame sequence (description.frames; none: one frame at the camera's shutter): frame k
// is captured as capture() would at description.frameCamera(k), named NAME_NNNN (the
// sequence frame number first + k), its sensor noise frame sensor.frame + k·(brackets or 1)
// — temporal noise differs per frame, the fixed pattern (noise seed) does not — and handed
// to onFrame(result, k) as soon as it is done. The Scene is built once (files read once) and
// moved to each frame's exposure window (Scene::setCamera: keyframed shapes built again
// over it, so that a frame's pose is never interpolated across keyframes outside it); a
// frame's step 4 re-renders on it (its shapes over the bracket's window). When nothing
// moves anywhere in the sequence, frame 0's film is reused for every frame (one render). A cancelled
// frame is handed on (cancelled) and ends it.
SequenceSummary captureSequence(SceneDescription description, const CaptureOptions& options,
                                const std::function<void(CaptureResult&&, int)>& onFrame);

// CIE XYZ (D65-referred, absolute) → ACEScg with the mean luminance exposed to 0.18.
Image xyzToExposedAcescg(const Image& xyz, double& exposure);

}  // namespace camsim
