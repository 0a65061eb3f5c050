#include "integrator/dataset/manifest.h"

#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include "integrator/scene/scene_loader.h"
#include "sensor/base/counter_rng.h"
#include "sensor/base/yaml_reader.h"

namespace camsim {
namespace {

// One `random.draw` entry: how to draw the value at `path` (checked when parsed).
struct Draw {
  enum class Kind { kUniform, kLogUniform, kNormal, kChoice, kOrbit } kind = Kind::kUniform;
  std::string path, key;
  SourceLocation where;
  double lo = 0.0, hi = 0.0;                      // uniform, log_uniform; normal: min, max
  double mean = 0.0, sd = 1.0;                    // normal
  std::vector<std::vector<std::string>> choices;  // choice: per option the values (YAML text)
  std::vector<std::string> paths;                 // choice over "a, b": the zipped key paths
  glm::dvec3 centre{0.0};                         // orbit
  std::pair<double, double> radius, azimuth, elevation;
};

// A key "a.b, c.d" names several key paths set together (zipped): a grid axis or a choice
// whose every value is a list with one entry per path.
std::vector<std::string> zippedPaths(const std::string& key, const YamlValue& where) {
  std::vector<std::string> paths;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = key.find(',', start);
    std::string p =
        key.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    while (!p.empty() && p.front() == ' ') p.erase(p.begin());
    while (!p.empty() && p.back() == ' ') p.pop_back();
    (void)parseKeyPath(p, where.where(), where.key());
    paths.push_back(p);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return paths;
}

std::vector<std::string> zippedValues(const std::vector<std::string>& paths, const YamlValue& v) {
  if (paths.size() == 1) return {yamlFlowText(v)};
  const std::vector<YamlValue> items = v.isSequence() ? v.items() : std::vector<YamlValue>{};
  if (items.size() != paths.size())
    v.fail("expected a list of " + std::to_string(paths.size()) + " values, one per key path");
  std::vector<std::string> out;
  for (const YamlValue& x : items) out.push_back(yamlFlowText(x));
  return out;
}

// [lo, hi] with lo ≤ hi (and lo > 0 when `positive` names what needs it).
std::pair<double, double> range(const YamlValue& v, const char* positive = nullptr) {
  const std::vector<double> r = v.numbers();
  if (r.size() != 2) v.fail("expected [lo, hi]");
  if (!(r[0] <= r[1])) v.fail("expected lo <= hi");
  if (positive && !(r[0] > 0.0)) v.fail(std::string(positive) + " must be positive");
  return {r[0], r[1]};
}

double normalCdf(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

Draw parseDraw(const std::string& path, const YamlValue& spec) {
  Draw d;
  d.path = path;
  d.key = spec.key();
  d.where = spec.where();
  YamlMap m(spec);
  const std::vector<std::string> keys = m.keys();
  if (keys.size() != 1)
    spec.fail(
        "a draw is one of {uniform: [a, b]}, {log_uniform: [a, b]}, "
        "{normal: {mean, sd, min, max}}, {choice: [...]}, {orbit: {...}}");
  const std::string kind = keys.front();
  const YamlValue v = *m.find(kind);
  if (path.find(',') != std::string::npos && kind != "choice")
    v.fail("several key paths at once (\"a, b\") take a choice of lists");
  if (kind == "uniform") {
    d.kind = Draw::Kind::kUniform;
    std::tie(d.lo, d.hi) = range(v);
  } else if (kind == "log_uniform") {
    d.kind = Draw::Kind::kLogUniform;
    std::tie(d.lo, d.hi) = range(v, "a log-uniform range");
  } else if (kind == "normal") {
    d.kind = Draw::Kind::kNormal;
    YamlMap n(v);
    d.mean = n.require("mean").number();
    d.sd = n.require("sd").number(0.0, 1e300, true);
    d.lo = n.find("min") ? n.find("min")->number() : -1e300;
    d.hi = n.find("max") ? n.find("max")->number() : 1e300;
    n.finish({"mean", "sd", "min", "max"});
    if (!(d.lo < d.hi)) v.fail("expected min < max");
    const double mass = normalCdf((d.hi - d.mean) / d.sd) - normalCdf((d.lo - d.mean) / d.sd);
    if (!(mass >= 1e-3)) v.fail("[min, max] keeps less than 0.1 % of this normal distribution");
  } else if (kind == "choice") {
    d.kind = Draw::Kind::kChoice;
    d.paths = zippedPaths(path, spec);
    for (const YamlValue& c : v.items()) d.choices.push_back(zippedValues(d.paths, c));
    if (d.choices.empty()) v.fail("a choice needs at least one value");
  } else if (kind == "orbit") {
    d.kind = Draw::Kind::kOrbit;
    const std::string suffix = "position";
    if (path.find(',') != std::string::npos) v.fail("an orbit draws one key path");
    if (path.size() < suffix.size() ||
        path.compare(path.size() - suffix.size(), suffix.size(), suffix) != 0)
      v.fail("an orbit draws a camera position: its key path ends in 'position'");
    YamlMap o(v);
    d.centre = o.require("centre").vec3();
    d.radius = range(o.require("radius"), "an orbit's radius range (m)");
    d.azimuth = o.find("azimuth_deg") ? range(*o.find("azimuth_deg")) : std::pair{0.0, 360.0};
    d.elevation = o.find("elevation_deg") ? range(*o.find("elevation_deg")) : std::pair{0.0, 0.0};
    if (d.elevation.first < -90.0 || d.elevation.second > 90.0)
      o.self().fail("elevation_deg must lie in [-90, 90]");
    o.finish({"centre", "radius", "azimuth_deg", "elevation_deg"});
  } else {
    m.self().fail("unknown draw '" + kind +
                  "' (known: uniform, log_uniform, normal, choice, orbit)");
  }
  return d;
}

std::string vec3Text(const glm::dvec3& v) {
  return "[" + yamlNumber(v.x) + ", " + yamlNumber(v.y) + ", " + yamlNumber(v.z) + "]";
}

// Draw j of item i: its edits (an orbit sets position and look_at).
std::vector<YamlEdit> drawValue(const Draw& d, std::uint64_t seed, std::size_t item,
                                std::size_t j) {
  CounterRng rng(streamKey(seed, item, j + 1));
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniformOpen(); };
  std::string value;
  switch (d.kind) {
    case Draw::Kind::kUniform:
      value = yamlNumber(uniform(d.lo, d.hi));
      break;
    case Draw::Kind::kLogUniform:
      value = yamlNumber(std::exp(uniform(std::log(d.lo), std::log(d.hi))));
      break;
    case Draw::Kind::kNormal: {
      double x = d.mean;
      for (int tries = 0; tries < 100000; ++tries) {  // ≥ 0.1 % mass: ends in ~1000 at worst
        x = d.mean + d.sd * rng.normal();
        if (x >= d.lo && x <= d.hi) break;
        x = std::clamp(x, d.lo, d.hi);
      }
      value = yamlNumber(x);
      break;
    }
    case Draw::Kind::kChoice: {
      const auto n = static_cast<double>(d.choices.size());
      const auto k = static_cast<std::size_t>(std::min(n - 1.0, std::floor(rng.uniformOpen() * n)));
      std::vector<YamlEdit> edits;
      for (std::size_t p = 0; p < d.paths.size(); ++p)
        edits.push_back({d.paths[p], d.choices[k][p], d.where, d.key});
      return edits;
    }
    case Draw::Kind::kOrbit: {
      const double r = uniform(d.radius.first, d.radius.second);
      const double a = uniform(d.azimuth.first, d.azimuth.second) * std::numbers::pi / 180.0;
      const double e = uniform(d.elevation.first, d.elevation.second) * std::numbers::pi / 180.0;
      const glm::dvec3 p = d.centre + r * glm::dvec3(std::sin(a) * std::cos(e), std::sin(e),
                                                     -std::cos(a) * std::cos(e));
      const std::string parent = d.path.substr(0, d.path.size() - std::string("position").size());
      return {{d.path, vec3Text(p), d.where, d.key},
              {parent + "look_at", vec3Text(d.centre), d.where, d.key}};
    }
  }
  return {{d.path, value, d.where, d.key}};
}

// A map of key path → value (set:, an explicit item) as edits.
std::vector<YamlEdit> editsOf(const YamlValue& value) {
  std::vector<YamlEdit> edits;
  YamlMap m(value);
  for (const std::string& path : m.keys()) {
    const YamlValue v = *m.find(path);
    (void)parseKeyPath(path, v.where(), v.key());
    edits.push_back({path, yamlFlowText(v), v.where(), v.key()});
  }
  return edits;
}

void addParameters(DatasetItem& item, const std::vector<YamlEdit>& edits) {
  for (const YamlEdit& e : edits) item.parameters.emplace_back(e.path, e.value);
}

}  // namespace

Manifest parseManifest(const std::string& text, const std::string& displayName,
                       const std::filesystem::path& baseDir) {
  Manifest m;
  m.file = displayName;
  m.text = text;
  const YamlValue root = parseYaml(text, displayName);
  if (root.isNull()) root.fail("the manifest is empty");
  YamlMap top(root);
  const YamlValue format = top.require("format");
  if (format.string() != "camsim-dataset/1")
    format.fail("unsupported format '" + format.string() +
                "' (this camsim reads camsim-dataset/1)");
  const YamlValue scene = top.require("scene");
  m.scene = baseDir / scene.string();
  m.sceneWhere = scene.where();
  try {
    m.sceneText = readSceneFile(m.scene);
  } catch (const InputError& e) {
    scene.fail("cannot read the base scene '" + m.scene.string() + "'");
  }
  if (auto v = top.find("seed")) m.seed = static_cast<std::uint64_t>(v->integer(0, INT64_MAX));
  if (auto v = top.find("seeds"))
    m.seedsPerItem = v->choice<bool>("seeds", {{"per_item", true}, {"fixed", false}});

  std::vector<YamlEdit> common;
  if (auto v = top.find("set")) common = editsOf(*v);
  std::vector<std::pair<std::vector<YamlEdit>, SourceLocation>> explicitItems;
  if (auto v = top.find("items"))
    for (const YamlValue& item : v->items())
      explicitItems.emplace_back(editsOf(item), item.where());

  // The grid: key paths and their value lists, as combinations (first key slowest).
  std::vector<std::vector<std::vector<YamlEdit>>> axes;  // per axis, per value: its edits
  std::optional<SourceLocation> gridWhere;
  if (auto v = top.find("grid")) {
    gridWhere = v->where();
    YamlMap g(*v);
    for (const std::string& path : g.keys()) {
      const YamlValue values = *g.find(path);
      const std::vector<std::string> paths = zippedPaths(path, values);
      std::vector<std::vector<YamlEdit>> axis;
      for (const YamlValue& x : values.items()) {
        const std::vector<std::string> texts = zippedValues(paths, x);
        std::vector<YamlEdit> cell;
        for (std::size_t p = 0; p < paths.size(); ++p)
          cell.push_back({paths[p], texts[p], x.where(), x.key()});
        axis.push_back(std::move(cell));
      }
      if (axis.empty()) values.fail("a grid axis needs at least one value");
      axes.push_back(std::move(axis));
    }
  }
  std::vector<Draw> draws;
  std::size_t drawCount = 0;
  std::optional<SourceLocation> randomWhere;
  if (auto v = top.find("random")) {
    randomWhere = v->where();
    YamlMap r(*v);
    drawCount = 1;
    if (auto c = r.find("count"))
      drawCount = static_cast<std::size_t>(c->integer(1, kMaxDatasetItems));
    if (auto d = r.find("draw")) {
      YamlMap dm(*d);
      for (const std::string& path : dm.keys()) {
        const YamlValue spec = *dm.find(path);
        if (path.find(',') == std::string::npos) (void)parseKeyPath(path, spec.where(), spec.key());
        draws.push_back(parseDraw(path, spec));
      }
    }
    r.finish({"count", "draw"});
  }
  top.finish({"format", "scene", "seed", "seeds", "set", "items", "grid", "random"});

  std::size_t combinations = axes.empty() ? (randomWhere ? 1 : 0) : 1;
  for (const auto& axis : axes) {
    if (combinations > kMaxDatasetItems / axis.size())
      top.self().fail(
          "the grid has more than 100000 items (split the dataset into several manifests)");
    combinations *= axis.size();
  }
  const std::size_t perCombination = randomWhere ? drawCount : 1;
  if (combinations > 0 && perCombination > kMaxDatasetItems / combinations)
    top.self().fail(
        "the manifest has more than 100000 items (split the dataset into several manifests)");
  const std::size_t total = explicitItems.size() + combinations * perCombination;
  if (total == 0) top.self().fail("the manifest has no items: give items, grid or random");
  if (total > kMaxDatasetItems)
    top.self().fail(
        "the manifest has more than 100000 items (split the dataset into several manifests)");

  // Whether the item's edits leave map.key as they give it: the last edit of the key, or of
  // the whole map, decides (a map edit without the key drops an earlier edit of it; found in
  // review). Map values are parsed once per distinct text.
  std::map<std::string, bool> mapHasSeed;  // (key, map value) → the value holds the key
  const auto itemSets = [&](const DatasetItem& item, const std::string& map, const char* key) {
    for (auto e = item.edits.rbegin(); e != item.edits.rend(); ++e) {
      if (e->path == map + "." + key) return true;
      if (e->path != map) continue;
      const auto [it, added] = mapHasSeed.try_emplace(std::string(key) + "\n" + e->value);
      if (added) {
        const YamlValue v = parseYaml(e->value, m.file.string());
        it->second = v.isMap() && YamlMap(v).has(key);
      }
      return it->second;
    }
    return false;
  };
  auto finishItem = [&](DatasetItem& item) {
    if (!m.seedsPerItem) return;
    // Last, so that an edit replacing the whole render or sensor map (or adding the sensor)
    // keeps them (found by probing: `set: {render: {spp: 2}}` rendered every item with seed
    // 0, identical pictures, while params.json listed the seeds); an item's own seed wins.
    const std::string seedKey = "seeds (dataset seed " + std::to_string(m.seed) + ")";
    if (!itemSets(item, "render", "seed"))
      item.edits.push_back({"render.seed", std::to_string(streamKey(m.seed, item.index, 0) >> 1),
                            item.where, seedKey});
    if (!itemSets(item, "sensor", "noise_seed"))
      item.edits.push_back({"sensor.noise_seed",
                            std::to_string(streamKey(m.seed, item.index, kNoiseStream) >> 1),
                            item.where, seedKey, true});
  };
  for (const auto& [edits, where] : explicitItems) {
    DatasetItem item;
    item.index = m.items.size();
    item.where = where;
    item.edits = common;
    item.edits.insert(item.edits.end(), edits.begin(), edits.end());
    addParameters(item, edits);
    finishItem(item);
    m.items.push_back(std::move(item));
  }
  for (std::size_t c = 0; c < combinations; ++c) {
    std::vector<YamlEdit> cell;
    std::size_t rest = c;
    for (std::size_t a = axes.size(); a-- > 0;) {  // last axis fastest
      const std::vector<YamlEdit>& value = axes[a][rest % axes[a].size()];
      cell.insert(cell.begin(), value.begin(), value.end());
      rest /= axes[a].size();
    }
    for (std::size_t r = 0; r < perCombination; ++r) {
      DatasetItem item;
      item.index = m.items.size();
      item.where = gridWhere ? *gridWhere : *randomWhere;
      item.edits = common;
      item.edits.insert(item.edits.end(), cell.begin(), cell.end());
      addParameters(item, cell);
      for (std::size_t j = 0; j < draws.size(); ++j) {
        const std::vector<YamlEdit> drawn = drawValue(draws[j], m.seed, item.index, j);
        item.edits.insert(item.edits.end(), drawn.begin(), drawn.end());
        addParameters(item, drawn);
      }
      finishItem(item);
      m.items.push_back(std::move(item));
    }
  }
  return m;
}

Manifest loadManifest(const std::filesystem::path& file) {
  std::string text;
  try {
    text = readSceneFile(file);
  } catch (const InputError&) {
    throw InputError({file.string(), 0, 0}, "", "cannot open the manifest");
  }
  return parseManifest(text, file.string(), sceneBaseDir(file));
}

}  // namespace camsim
