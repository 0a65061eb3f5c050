// Tile parts: one frame rendered across processes and put back together (camsim render
// --tiles k/M, camsim merge; docs/output.md). A part holds what renderCaptureFilms()
// (capture.h) gives for tile share k of M (Share, sensor/base/share.h) — the films
// themselves, as 32-bit float, so they come back bit for bit — in NAME.part-k-of-M.exr:
//
// | channels      | what |
// |---------------|------|
// | film.<c>      | CaptureResult::film: CIE XYZ (film.X, film.Y, film.Z), absolute |
// | sensor.<c>    | with a sensor: sensorFilm, the expected electrons at the scene's exposure |
// | aov.<c>       | with render.aovs: every channel of aovs (ID mattes included) |
//
// The share's tiles hold the values, every other pixel is 0. Header (strings):
// camsim:version, camsim:name, camsim:scene (the path as the render was given it),
// camsim:scene_fnv1a64, camsim:overrides (the front end's changes to the loaded scene:
// overridesText(), one "key=value" line each, integrator/scene/overrides.h), camsim:spp, camsim:seed, camsim:resolution ("W H"),
// camsim:tile_size, camsim:tile_count (M), camsim:tile_index (k), camsim:tiles (in words),
// camsim:modelled and camsim:modelled_dims (what was integrated: the capture's step 4
// needs it), camsim:film_channels, camsim:sensor_channels, camsim:aov_channels (each
// image's channels in order, comma-separated), camsim:samples and camsim:rejected_samples
// (this part's), camsim:render_seconds (this part's; left out when reproducible).
//
// assembleTileParts() reads parts and checks that they are all parts of one render — every
// header attribute but the part's own (index, tiles, samples, rejected samples, seconds)
// equal — and that every k in 0..M-1 is there exactly once; then takes each tile from the
// part that holds it. mergedCapture() checks the reloaded scene against them and gives the
// CaptureResult that finishCapture() completes: with the same build, scene, seed and
// overrides it equals the one-process capture bit for bit.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "integrator/capture/capture.h"
#include "integrator/scene/overrides.h"

namespace camsim {

// NAME.part-k-of-M.exr
std::string tilePartFileName(const std::string& name, Share share);

struct TilePartOptions {
  std::filesystem::path directory;  // created if missing
  Overrides overrides;              // camsim:overrides (overridesText)
  bool reproducible = false;        // leave out camsim:render_seconds
};

// Writes `result` (renderCaptureFilms with options.tiles = share, not cancelled) as
// directory/tilePartFileName(...) through an OutputSet. Returns the file.
std::filesystem::path writeTilePart(const CaptureResult& result, Share share,
                                    const TilePartOptions& options);

// What the parts say about the render they are shares of (part 0's header).
struct TilePartHeader {
  std::string version, name, scene, sceneFnv1a;
  std::string overridesText;  // camsim:overrides as stored
  Overrides overrides;        // read back (parseOverridesText): what merge applies
  glm::ivec2 resolution{0};
  int spp = 0;
  std::uint64_t seed = 0;
  int tileCount = 1;  // M
  ModelledDimensions modelled;
  std::optional<GuideStats> guide;  // camsim:guide (a guided render), trainSeconds 0
  std::vector<std::string> filmChannels, sensorChannels, aovChannels, halfChannels;
};

struct AssembledTiles {
  TilePartHeader header;
  std::vector<std::filesystem::path> files;  // in share order: files[k] holds share k
  Image film, sensorFilm, aovs, oddHalf;     // every tile from its part
  std::uint64_t samples = 0, rejectedSamples = 0;
  double renderSeconds = 0.0;      // the parts' render times summed (those that have one)
  double guideTrainSeconds = 0.0;  // likewise their guides' training times
};

// Throws InputError naming the file (for a missing part, the file it would be, beside the
// first) and the attribute: not a tile part, made by another camsim version than this
// one, a part of another render (an attribute differs from the first file's), a share
// given twice or missing. Holds one part in memory at a time besides the result.
AssembledTiles assembleTileParts(const std::vector<std::filesystem::path>& files);

// The capture of `description` — the scene the parts' header names, loaded again with
// their overrides — with the assembled films and stats, ready for finishCapture().
// InputError naming the scene file when it is not the parts' scene (the file changed
// since: its FNV-1a differs; or its name, resolution, spp, seed, sensor differ), or when
// the capture cannot be finished from tiles (checkTileable).
CaptureResult mergedCapture(AssembledTiles tiles, SceneDescription description);

// "aperture=1 blades=6 time=1 moving_objects=2 camera_moves=0 rolling_shutter=0
// wavelengths=4 time_steps=2 diffraction=0 spectral_cv=1 lens_surfaces=11 lens_disperses=1"
// and back (nullopt when it does not read, e.g. a part of an older build with fewer fields,
// or is not what a render models: no wavelength, time without anything moving). The traced
// lens's name is not in it (a file name may hold spaces): camsim:traced_lens.
std::string modelledDimsText(const ModelledDimensions& m);
std::optional<ModelledDimensions> parseModelledDims(const std::string& text);
// "train_spp=63 iterations=6 records=… leaves=… bytes=…" (camsim:guide) and back; the
// training time is a part's own (camsim:guide_train_seconds).
std::string guideStatsText(const GuideStats& g);
std::optional<GuideStats> parseGuideStats(const std::string& text);

}  // namespace camsim
