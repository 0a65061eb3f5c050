// Tile parts (tile_parts.h): a share's films written as one float EXR, read back, checked
// against the other parts and the scene, and assembled tile by tile.
#include "integrator/capture/tile_parts.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "integrator/scene/setting_ranges.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/output_set.h"
#include "sensor/model/sensor_spec.h"
#include "sensor/model/spectral_response.h"

namespace camsim {
namespace {

// The images of a part and the prefixes of their channels in the EXR: the film, the sensor
// film, the AOVs, and the error channel's odd-sample mean (for the merged render's error
// estimate, error_estimate.h).
constexpr int kImages = 4;
constexpr const char* kPrefixes[kImages] = {"film.", "sensor.", "aov.", "half."};
constexpr const char* kChannelKeys[kImages] = {"camsim:film_channels", "camsim:sensor_channels",
                                               "camsim:aov_channels", "camsim:half_channels"};
// The attributes that differ between the parts of one render; all others must agree.
const std::set<std::string> kPerPart = {"camsim:tile_index",     "camsim:tiles",
                                        "camsim:samples",        "camsim:rejected_samples",
                                        "camsim:render_seconds", "camsim:guide_train_seconds"};

constexpr int kMaxTileCount = 1 << 20;  // as camsim render --tiles takes M
// |film value| a part may hold: beyond it the XYZ → RGB conversion (rows of absolute sum < 8)
// could overflow float. Film values are luminous energy on a photosite (lm·s, output.md); a
// render's are not otherwise bounded (emission scales and light intensities up to 1e30).
constexpr float kMaxFilmValue = std::numeric_limits<float>::max() / 8.0f;

// Compared first, so that a part of another render is told by what matters most.
constexpr const char* kFirstCompared[] = {
    "camsim:tile_count", "camsim:scene", "camsim:scene_fnv1a64", "camsim:resolution",
    "camsim:spp",        "camsim:seed",  "camsim:overrides",     "camsim:name"};

std::string joined(const std::vector<std::string>& names, const std::string& scene) {
  std::string out;
  for (const std::string& n : names) {
    if (n.find(',') != std::string::npos)
      throw InputError({scene, 0, 0}, "",
                       "channel name '" + n + "' has a comma: it cannot go into a tile part");
    out += (out.empty() ? "" : ",") + n;
  }
  return out;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  if (text.empty()) return out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) out.push_back(item);
  return out;
}

template <typename T>
std::optional<T> parseNumber(const std::string& text) {
  T v{};
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  return v;
}

// Copies the pixels of `rect` from `from` to `to` (same size and channels).
void copyRect(const Image& from, Image& to, TileRect rect) {
  const std::size_t n = from.channels.size();
  if (n == 0) return;
  for (int y = rect.lo.y; y < rect.hi.y; ++y) {
    const std::size_t begin = from.index(rect.lo.x, y, 0);
    const std::size_t count = static_cast<std::size_t>(rect.hi.x - rect.lo.x) * n;
    std::copy_n(from.pixels.begin() + static_cast<std::ptrdiff_t>(begin), count,
                to.pixels.begin() + static_cast<std::ptrdiff_t>(begin));
  }
}

// "key=value …" (camsim:modelled_dims, camsim:guide): the values of exactly `keys`, each
// once, as T; nullopt for anything else (an unknown, missing or repeated key, a bad value).
template <typename T>
std::optional<std::map<std::string, T>> readFields(const std::string& text,
                                                   std::initializer_list<const char*> keys) {
  std::map<std::string, T> out;
  std::istringstream in(text);
  std::string item;
  while (in >> item) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) return std::nullopt;
    const std::string key = item.substr(0, eq);
    const std::optional<T> v = parseNumber<T>(item.substr(eq + 1));
    if (!v || std::find(keys.begin(), keys.end(), key) == keys.end() ||
        !out.emplace(key, *v).second)
      return std::nullopt;
  }
  if (out.size() != keys.size()) return std::nullopt;
  return out;
}

struct ReadPart {
  std::map<std::string, std::string> attrs;  // camsim:* attributes
  TilePartHeader header;
  int index = 0;
  std::uint64_t samples = 0, rejected = 0;
  std::optional<double> seconds, guideSeconds;
  Image images[kImages];  // film, sensor film, aovs, odd half
};

ReadPart readPart(const std::filesystem::path& file) {
  const ExrFile exr = readExr(file);
  ReadPart p;
  for (const auto& [key, value] : exr.metadata)
    if (key.rfind("camsim:", 0) == 0) p.attrs[key] = value;
  const auto get = [&](const std::string& key) -> const std::string& {
    const auto it = p.attrs.find(key);
    if (it == p.attrs.end())
      throw InputError({file.string(), 0, 0}, key,
                       "not a camsim tile part (camsim render --tiles k/M writes them): no " + key +
                           " attribute");
    return it->second;
  };
  const auto bad = [&](const std::string& key) {
    return InputError({file.string(), 0, 0}, key, "unreadable value '" + get(key) + "'");
  };
  // An integer in [lo, hi] (an spp of 4294967298 was cut to 2 and merged; an index past the
  // count said "unreadable value").
  const auto integer = [&](const std::string& key, std::int64_t lo, std::int64_t hi) {
    const std::optional<std::int64_t> v = parseNumber<std::int64_t>(get(key));
    if (!v) throw bad(key);
    if (*v < lo || *v > hi)
      throw InputError({file.string(), 0, 0}, key,
                       "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                           "], got " + get(key));
    return *v;
  };
  constexpr std::int64_t kAny = std::numeric_limits<std::int64_t>::max();
  TilePartHeader& h = p.header;
  const std::int64_t count = integer("camsim:tile_count", 1, kMaxTileCount);
  const std::int64_t index = integer("camsim:tile_index", 0, count - 1);
  h.tileCount = static_cast<int>(count);
  p.index = static_cast<int>(index);
  h.version = get("camsim:version");
  if (h.version != CAMSIM_VERSION)
    throw InputError({file.string(), 0, 0}, "camsim:version",
                     "rendered by camsim " + h.version +
                         ", this is camsim " CAMSIM_VERSION
                         ": merge the parts with the build that rendered them (the bytes depend on "
                         "it)");
  h.name = get("camsim:name");
  h.scene = get("camsim:scene");
  h.sceneFnv1a = get("camsim:scene_fnv1a64");
  h.overridesText = get("camsim:overrides");
  h.overrides = parseOverridesText(h.overridesText, file.string() + " camsim:overrides");
  h.spp = static_cast<int>(integer("camsim:spp", 1, setting_ranges::kSpp.hi));
  h.seed = static_cast<std::uint64_t>(integer("camsim:seed", 0, kAny));
  (void)integer("camsim:tile_size", kRenderTileSize, kRenderTileSize);
  std::istringstream res(get("camsim:resolution"));
  if (!(res >> h.resolution.x >> h.resolution.y) ||
      h.resolution != glm::ivec2(exr.image.width, exr.image.height))
    throw bad("camsim:resolution");
  const std::optional<ModelledDimensions> dims = parseModelledDims(get("camsim:modelled_dims"));
  if (!dims) throw bad("camsim:modelled_dims");
  h.modelled = *dims;
  p.samples = static_cast<std::uint64_t>(integer("camsim:samples", 0, kAny));
  p.rejected = static_cast<std::uint64_t>(integer("camsim:rejected_samples", 0, kAny));
  const auto seconds = [&](const char* key, std::optional<double>& out) {
    if (!p.attrs.count(key)) return;  // nan, -5 or 1e308 printed nonsense times
    out = parseNumber<double>(get(key));
    if (!out || !(*out >= 0.0 && *out <= 1e9)) throw bad(key);
  };
  seconds("camsim:render_seconds", p.seconds);
  seconds("camsim:guide_train_seconds", p.guideSeconds);
  h.modelled.tracedLens = get("camsim:traced_lens");
  if (p.attrs.count("camsim:guide")) {
    const std::optional<GuideStats> guide = parseGuideStats(get("camsim:guide"));
    if (!guide) throw bad("camsim:guide");
    h.guide = *guide;
  }
  std::vector<std::string>* lists[kImages] = {&h.filmChannels, &h.sensorChannels, &h.aovChannels,
                                              &h.halfChannels};
  for (int i = 0; i < kImages; ++i) {
    *lists[i] = split(get(kChannelKeys[i]));
    if (lists[i]->empty()) continue;
    // A name listed twice would reach the EXR writer, whose error names neither file nor key.
    for (auto it = lists[i]->begin(); it != lists[i]->end(); ++it)
      if (std::find(lists[i]->begin(), it, *it) != it)
        throw InputError({file.string(), 0, 0}, kChannelKeys[i],
                         "names channel " + std::string(kPrefixes[i]) + *it +
                             " twice: not as camsim render --tiles writes it");
    Image& image = p.images[i];
    image = Image(h.resolution.x, h.resolution.y, *lists[i]);
    const std::size_t n = lists[i]->size(), m = exr.image.channels.size();
    for (std::size_t c = 0; c < n; ++c) {
      const int from = exr.image.channelIndex(kPrefixes[i] + (*lists[i])[c]);
      if (from < 0)
        throw InputError({file.string(), 0, 0}, kChannelKeys[i],
                         "no channel " + std::string(kPrefixes[i]) + (*lists[i])[c]);
      for (std::size_t px = 0; px < image.pixels.size() / n; ++px) {
        const float v = exr.image.pixels[px * m + static_cast<std::size_t>(from)];
        // A render writes finite values only (it rejects non-finite samples; an AOV pixel
        // no sample hit holds 0: output.md); one that is not would pass into the merge.
        // Nor a film value near the float range (found by probing: 3e38 merged into an inf
        // R channel, exit 0).
        if (!std::isfinite(v) || (i == 0 && std::abs(v) > kMaxFilmValue))
          throw InputError(
              {file.string(), 0, 0}, std::string(kPrefixes[i]) + (*lists[i])[c],
              "pixel (" + std::to_string(px % static_cast<std::size_t>(h.resolution.x)) + ", " +
                  std::to_string(px / static_cast<std::size_t>(h.resolution.x)) + ") is " +
                  (std::isfinite(v) ? "beyond float's largest / 8" : "not finite") +
                  ": not as camsim render --tiles writes it");
        image.pixels[px * n + c] = v;
      }
    }
  }
  if (h.filmChannels.empty()) throw bad("camsim:film_channels");
  // Lists a render does not write would fail an internal check later (the colour conversion
  // needs X, Y, Z; the error estimate one channel of the film): refused here by key.
  const auto notAsWritten = [&](const char* key, const std::string& why) {
    return InputError({file.string(), 0, 0}, key, "'" + get(key) + "': " + why);
  };
  if (h.filmChannels != SpectralResponse::cieXyz().storedChannelNames())
    throw notAsWritten("camsim:film_channels", "camsim render --tiles writes X,Y,Z");
  if (h.halfChannels.size() > 1)
    throw notAsWritten("camsim:half_channels", "camsim render --tiles writes one channel at most");
  if (h.halfChannels.size() == 1 && std::find(h.filmChannels.begin(), h.filmChannels.end(),
                                              h.halfChannels[0]) == h.filmChannels.end())
    throw notAsWritten("camsim:half_channels",
                       "camsim render --tiles writes one of the film's channels");
  return p;
}

std::string shareName(int k, int m) {
  return "part " + std::to_string(k) + " of " + std::to_string(m);
}

}  // namespace

std::string tilePartFileName(const std::string& name, Share share) {
  return name + ".part-" + std::to_string(share.index) + "-of-" + std::to_string(share.count) +
         ".exr";
}

std::string modelledDimsText(const ModelledDimensions& m) {
  return "aperture=" + std::to_string(int(m.aperture)) + " blades=" + std::to_string(m.blades) +
         " time=" + std::to_string(int(m.time)) +
         " moving_objects=" + std::to_string(m.movingObjects) +
         " camera_moves=" + std::to_string(int(m.cameraMoves)) +
         " rolling_shutter=" + std::to_string(int(m.rollingShutter)) +
         " wavelengths=" + std::to_string(m.wavelengths) +
         " time_steps=" + std::to_string(m.timeSteps) +
         " diffraction=" + std::to_string(int(m.diffraction)) +
         " spectral_cv=" + std::to_string(int(m.spectralControlVariate)) +
         " lens_surfaces=" + std::to_string(m.lensSurfaces) +
         " lens_disperses=" + std::to_string(int(m.lensDisperses));
}

std::optional<ModelledDimensions> parseModelledDims(const std::string& text) {
  const std::optional<std::map<std::string, int>> f =
      readFields<int>(text, {"aperture", "blades", "time", "moving_objects", "camera_moves",
                             "rolling_shutter", "wavelengths", "time_steps", "diffraction",
                             "spectral_cv", "lens_surfaces", "lens_disperses"});
  if (!f) return std::nullopt;
  const std::map<std::string, int>& v = *f;
  ModelledDimensions m;
  m.aperture = v.at("aperture") != 0;
  m.blades = v.at("blades");
  m.time = v.at("time") != 0;
  m.movingObjects = v.at("moving_objects");
  m.cameraMoves = v.at("camera_moves") != 0;
  m.rollingShutter = v.at("rolling_shutter") != 0;
  m.wavelengths = v.at("wavelengths");
  m.timeSteps = v.at("time_steps");
  m.diffraction = v.at("diffraction") != 0;
  m.spectralControlVariate = v.at("spectral_cv") != 0;
  m.lensSurfaces = v.at("lens_surfaces");
  m.lensDisperses = v.at("lens_disperses") != 0;
  // What a render can have modelled (a hand-edited part merged "0 wavelengths").
  // (Scene::analyseExposure; RenderOptions::forceTime, the bench's, would fail the time
  // test, but the bench writes no part.)
  if (m.blades < 0 || m.movingObjects < 0 || m.wavelengths < 1 || m.timeSteps < 1 ||
      m.lensSurfaces < 0 || m.time != (m.movingObjects > 0 || m.cameraMoves) ||
      (m.rollingShutter && !m.time))
    return std::nullopt;
  return m;
}

std::string guideStatsText(const GuideStats& g) {
  return "train_spp=" + std::to_string(g.trainSpp) + " iterations=" + std::to_string(g.iterations) +
         " records=" + std::to_string(g.records) + " leaves=" + std::to_string(g.leaves) +
         " bytes=" + std::to_string(g.bytes);
}

std::optional<GuideStats> parseGuideStats(const std::string& text) {
  const std::optional<std::map<std::string, std::uint64_t>> f =
      readFields<std::uint64_t>(text, {"train_spp", "iterations", "records", "leaves", "bytes"});
  if (!f) return std::nullopt;
  const std::map<std::string, std::uint64_t>& v = *f;
  for (const auto& [key, value] : v)
    if (value > (1ull << 62)) return std::nullopt;
  if (v.at("train_spp") > (1u << 30) || v.at("iterations") > 30) return std::nullopt;
  GuideStats g;
  g.trainSpp = static_cast<int>(v.at("train_spp"));
  g.iterations = static_cast<int>(v.at("iterations"));
  g.records = v.at("records");
  g.leaves = static_cast<std::size_t>(v.at("leaves"));
  g.bytes = static_cast<std::size_t>(v.at("bytes"));
  return g;
}

std::filesystem::path writeTilePart(const CaptureResult& r, Share share,
                                    const TilePartOptions& options) {
  CAMSIM_CHECK(!r.cancelled && !r.film.pixels.empty());
  const SceneDescription& desc = r.description;
  const Image* images[kImages] = {&r.film, &r.sensorFilm, &r.aovs, &r.oddHalf};
  std::vector<std::string> names;
  std::string lists[kImages];
  for (int i = 0; i < kImages; ++i) {
    lists[i] = joined(images[i]->channels, desc.sourceFile);
    for (const std::string& c : images[i]->channels) names.push_back(kPrefixes[i] + c);
  }
  const int w = r.film.width, h = r.film.height;
  Image part(w, h, names);
  const std::size_t n = names.size();
  for (std::size_t px = 0; px < static_cast<std::size_t>(w) * static_cast<std::size_t>(h); ++px) {
    std::size_t c = 0;
    for (const Image* image : images) {
      const std::size_t m = image->channels.size();
      for (std::size_t k = 0; k < m; ++k) part.pixels[px * n + c++] = image->pixels[px * m + k];
    }
  }
  const int tiles = renderTileCount({w, h});
  Metadata meta = {
      {"camsim:version", CAMSIM_VERSION},
      {"camsim:name", desc.name},
      {"camsim:scene", desc.sourceFile},
      {"camsim:scene_fnv1a64", desc.sourceFnv1a},
      {"camsim:overrides", overridesText(options.overrides)},
      {"camsim:spp", std::to_string(desc.render.spp)},
      {"camsim:seed", std::to_string(desc.render.seed)},
      {"camsim:resolution", std::to_string(w) + " " + std::to_string(h)},
      {"camsim:tile_size", std::to_string(kRenderTileSize)},
      {"camsim:tile_count", std::to_string(share.count)},
      {"camsim:tile_index", std::to_string(share.index)},
      {"camsim:tiles", std::to_string(share.itemsOf(tiles)) + " of the image's " +
                           std::to_string(tiles) + " tiles (" + std::to_string(kRenderTileSize) +
                           " px square, numbered by rows): those t with t % " +
                           std::to_string(share.count) + " == " + std::to_string(share.index) +
                           "; other pixels are 0"},
      {"camsim:modelled", r.stats.modelled.describe()},
      {"camsim:modelled_dims", modelledDimsText(r.stats.modelled)},
      {"camsim:traced_lens", r.stats.modelled.tracedLens},
      {"camsim:film_channels", lists[0]},
      {"camsim:sensor_channels", lists[1]},
      {"camsim:aov_channels", lists[2]},
      {"camsim:half_channels", lists[3]},
      {"camsim:samples", std::to_string(r.stats.samples)},
      {"camsim:rejected_samples", std::to_string(r.stats.rejectedSamples)},
      {"camsim:units",
       "a tile part of one frame (camsim merge assembles them): film.* the CIE XYZ film "
       "(NAME.exr's XYZ), sensor.* the expected electrons at the scene's exposure, aov.* the "
       "ground-truth layers of NAME.exr"}};
  if (r.stats.guide) meta.push_back({"camsim:guide", guideStatsText(*r.stats.guide)});
  if (!options.reproducible) {
    meta.push_back({"camsim:render_seconds", std::to_string(r.stats.seconds)});
    if (r.stats.guide)
      meta.push_back({"camsim:guide_train_seconds", std::to_string(r.stats.guide->trainSeconds)});
  }
  OutputSet outputs(options.directory);
  writeExr(outputs.add(tilePartFileName(desc.name, share)), part, meta, std::nullopt);
  return outputs.commit().front();
}

AssembledTiles assembleTileParts(const std::vector<std::filesystem::path>& files) {
  CAMSIM_CHECK(!files.empty());
  AssembledTiles out;
  std::map<std::string, std::string> first;  // the first part's shared attributes
  std::vector<std::optional<std::filesystem::path>> byShare;
  for (const std::filesystem::path& file : files) {
    ReadPart p = readPart(file);
    std::map<std::string, std::string> shared;
    for (const auto& [key, value] : p.attrs)
      if (!kPerPart.count(key)) shared[key] = value;
    if (byShare.empty()) {
      first = shared;
      out.header = p.header;
      byShare.resize(static_cast<std::size_t>(p.header.tileCount));
      Image* images[kImages] = {&out.film, &out.sensorFilm, &out.aovs, &out.oddHalf};
      for (int i = 0; i < kImages; ++i)
        if (!p.images[i].channels.empty())
          *images[i] = Image(p.header.resolution.x, p.header.resolution.y, p.images[i].channels);
    } else {
      // Every attribute of the first part, the same here (the telling ones first); and
      // none that it lacks.
      std::vector<std::pair<std::string, std::string>> order;
      for (const char* key : kFirstCompared)
        if (first.count(key)) order.emplace_back(key, first.at(key));
      order.insert(order.end(), first.begin(), first.end());
      for (const auto& [key, value] : order) {
        const auto it = shared.find(key);
        const std::string here = it == shared.end() ? "(none)" : it->second;
        if (here != value)
          throw InputError({file.string(), 0, 0}, key,
                           "not a part of the same render as " + files.front().string() + ": " +
                               key + " is '" + here + "' here, '" + value + "' there");
      }
      for (const auto& [key, value] : shared)
        if (!first.count(key))
          throw InputError({file.string(), 0, 0}, key,
                           "not a part of the same render as " + files.front().string() +
                               ": it has " + key + " '" + value + "', that one has none");
    }
    std::optional<std::filesystem::path>& slot = byShare[static_cast<std::size_t>(p.index)];
    if (slot)
      throw InputError(
          {file.string(), 0, 0}, "camsim:tile_index",
          shareName(p.index, p.header.tileCount) + " given twice: also " + slot->string());
    slot = file;
    const Share share{p.index, p.header.tileCount};
    const int tiles = renderTileCount(p.header.resolution);
    Image* images[kImages] = {&out.film, &out.sensorFilm, &out.aovs, &out.oddHalf};
    for (int i = 0; i < share.itemsOf(tiles); ++i)
      for (int k = 0; k < kImages; ++k)
        copyRect(p.images[k], *images[k], renderTileRect(p.header.resolution, share.item(i)));
    out.samples += p.samples;
    out.rejectedSamples += p.rejected;
    if (p.seconds) out.renderSeconds += *p.seconds;
    if (p.guideSeconds) out.guideTrainSeconds += *p.guideSeconds;
  }
  std::string given;
  for (std::size_t k = 0; k < byShare.size(); ++k)
    if (byShare[k]) given += (given.empty() ? "" : ", ") + std::to_string(k);
  for (std::size_t k = 0; k < byShare.size(); ++k)
    if (!byShare[k]) {
      const Share share{static_cast<int>(k), out.header.tileCount};
      const std::filesystem::path missing =
          files.front().parent_path() / tilePartFileName(out.header.name, share);
      throw InputError({missing.string(), 0, 0}, "camsim:tile_index",
                       shareName(share.index, share.count) + " is missing (given: part" +
                           (given.find(',') == std::string::npos ? " " : "s ") + given + ")");
    }
  for (const auto& f : byShare) out.files.push_back(*f);
  return out;
}

CaptureResult mergedCapture(AssembledTiles tiles, SceneDescription description) {
  const TilePartHeader& h = tiles.header;
  const SourceLocation where{description.sourceFile, 0, 0};
  const std::string parts = tiles.files.front().string();
  if (description.sourceFnv1a != h.sceneFnv1a)
    throw InputError(where, "",
                     "the scene file changed since the parts were rendered: its FNV-1a is " +
                         description.sourceFnv1a + ", the parts' (" + parts + ") " + h.sceneFnv1a +
                         "; restore it or render the parts again");
  const auto differs = [&](const std::string& what, const std::string& here,
                           const std::string& there) {
    return InputError(where, "",
                      "not the scene of the parts (" + parts + "): " + what + " " + here +
                          " here, " + there + " there");
  };
  const glm::ivec2 res = description.camera.resolution;
  if (description.name != h.name) throw differs("name", description.name, h.name);
  if (res != h.resolution)
    throw differs("resolution", std::to_string(res.x) + "x" + std::to_string(res.y),
                  std::to_string(h.resolution.x) + "x" + std::to_string(h.resolution.y));
  if (description.render.spp != h.spp)
    throw differs("spp", std::to_string(description.render.spp), std::to_string(h.spp));
  if (description.render.seed != h.seed)
    throw differs("seed", std::to_string(description.render.seed), std::to_string(h.seed));
  if (description.sensor.has_value() != !h.sensorChannels.empty())
    throw differs("sensor", description.sensor ? "one" : "none",
                  h.sensorChannels.empty() ? "none" : "one");
  if (description.sensor) {
    const std::vector<std::string> planes =
        sensorResponse(description.sensor->spec).storedChannelNames();
    if (h.sensorChannels != planes)
      throw InputError({parts, 0, 0}, "camsim:sensor_channels",
                       "'" + joined(h.sensorChannels, parts) + "': camsim render --tiles writes " +
                           joined(planes, parts) + " for the scene's sensor");
  }
  if (description.render.aovs.empty() != h.aovChannels.empty())
    throw differs("aovs", description.render.aovs.empty() ? "none" : "some",
                  h.aovChannels.empty() ? "none" : "some");
  checkTileable(description, h.modelled);
  CaptureResult out;
  out.description = std::move(description);
  out.description.releaseDecodedImages();
  out.stats.samples = tiles.samples;
  out.stats.spp = out.description.render.spp;  // parts are never rendered in passes
  out.stats.rejectedSamples = tiles.rejectedSamples;
  out.stats.modelled = h.modelled;
  out.stats.seconds = tiles.renderSeconds;
  if (h.guide) {  // every part trained the same guide; their training times summed
    out.stats.guide = *h.guide;
    out.stats.guide->trainSeconds = tiles.guideTrainSeconds;
  }
  out.tilesDone = out.tilesTotal = renderTileCount(h.resolution);
  out.film = std::move(tiles.film);
  out.sensorFilm = std::move(tiles.sensorFilm);
  if (!tiles.oddHalf.pixels.empty()) {  // as the whole render estimates its error
    const int y = out.film.channelIndex("Y");
    if (y >= 0)
      out.stats.estimatedError =
          ErrorEstimate{estimateFromHalves(out.film, y, tiles.oddHalf, out.stats.spp),
                        tiles.oddHalf.channels.front()};
  }
  out.aovs = std::move(tiles.aovs);
  return out;
}

}  // namespace camsim
