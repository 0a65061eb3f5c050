// Dataset manifests (docs/dataset-format.md): a base scene and the items of a dataset,
// each the base scene with some key paths set — an explicit list, a grid (cartesian
// product) and random draws — and its own seeds.
//
// | key            | unit | default  | meaning                                              |
// |----------------|------|----------|------------------------------------------------------|
// | format         | —    | required | camsim-dataset/1                                     |
// | scene          | —    | required | the base scene file, relative to the manifest        |
// | seed           | —    | 0        | the dataset seed                                     |
// | seeds          | —    | per_item | per_item: render.seed and sensor.noise_seed hashed    |
// |                |      |          | from (seed, item); fixed: the scene's own             |
// | set            | —    | {}       | key path → value, applied to every item first         |
// | items          | —    | []       | explicit items: each a map key path → value           |
// | grid           | —    | {}       | key path → list of values: one item per combination   |
// |                |      |          | (the first key varies slowest)                         |
// | random.count   | —    | 1        | draws per grid combination (or in all, without grid)  |
// | random.draw    | —    | {}       | key path → {uniform: [a, b]} | {log_uniform: [a, b]} | |
// |                |      |          | {normal: {mean, sd, min, max}} | {choice: [v, …]} |    |
// |                |      |          | {orbit: {centre, radius, azimuth_deg, elevation_deg}} |
// A grid or choice key "a.b, c.d" sets several key paths together: each value is a list with
// one entry per path (e.g. a sensor and the focal length that keeps the field of view).
// A null value removes the key from the base scene.
// Item order: the explicit items, then for each grid combination its random.count draws.
// Draw j of item i uses the stream CounterRng(streamKey(seed, i, j + 1)); the item's seeds
// are streamKey(seed, i, 0) and streamKey(seed, i, kNoiseStream), halved to fit int64 — so
// an item is the same whatever other items, shards or runs there are.
// orbit (on a key path ending in `position`): position = centre + r·(sin a·cos e, sin e,
// −cos a·cos e) with r, a, e uniform in their [lo, hi] (a about +y, 0 = on the −z side of
// the centre, e above the horizontal), and the sibling look_at = centre.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sensor/base/yaml_edit.h"

namespace camsim {

struct DatasetItem {
  std::size_t index = 0;
  std::vector<YamlEdit> edits;  // in order: set, the item's own, grid, draws, seeds
  // What makes this item differ, for its params.json: key path → value (YAML text).
  std::vector<std::pair<std::string, std::string>> parameters;
  SourceLocation where;  // the manifest entry it comes from (items[i], grid or random)
};

// The most items a manifest may have: items are expanded up front (~1 kB each).
inline constexpr std::size_t kMaxDatasetItems = 100000;

struct Manifest {
  std::filesystem::path file;   // as given
  std::string text;             // the manifest's own text
  std::filesystem::path scene;  // the base scene, resolved against the manifest's folder
  SourceLocation sceneWhere;    // the manifest's `scene:` value
  std::string sceneText;        // its text
  std::uint64_t seed = 0;
  bool seedsPerItem = true;
  std::vector<DatasetItem> items;
};

// Reads and checks a manifest and its base scene's YAML syntax; expands its items (no scene is
// loaded yet: resolveItem does that). InputError with file:line and key on bad input.
Manifest loadManifest(const std::filesystem::path& file);
// The same from text; relative paths resolve against baseDir.
Manifest parseManifest(const std::string& text, const std::string& displayName,
                       const std::filesystem::path& baseDir);

inline constexpr std::uint64_t kNoiseStream = 0x6e6f697365ull;  // "noise"

}  // namespace camsim
