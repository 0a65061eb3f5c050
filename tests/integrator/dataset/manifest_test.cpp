// Dataset manifests (integrator/dataset/manifest.cpp, dataset_item.cpp, sensor/base/yaml_edit.cpp):
//  - set, explicit items, a grid (first key slowest) and random draws resolve to the
//    documented items in the documented order, with the values in the resolved scene;
//  - draws stay in their ranges, and an item's draws and seeds depend only on (dataset
//    seed, item): the same manifest gives the same items, another seed other ones;
//  - an orbit puts the camera at its radius from the centre, looking at it; zipped keys
//    set their paths together; null removes a key;
//  - ten malformed manifests are rejected with the manifest's file:line and key;
//  - every manifest shipped in scenes/ resolves.
#include "integrator/dataset/dataset_item.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

const char* kManifestScene =
    "format: camsim-scene/1\n"
    "name: probe\n"
    "render: {spp: 4}\n"
    "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [16, 16], f_number: 4}\n"
    "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
    "shapes:\n"
    "  - {name: ball, type: sphere, centre: [0, 0, 0], radius: 1, emission: {luminance: 100}}\n"
    "  - {name: floor, type: rectangle, corner: [-2, -1, -2], edge_u: [0, 0, 4], edge_v: [4, 0, "
    "0], material: grey}\n";

class ManifestTest : public testing::Test {
 protected:
  void SetUp() override { test::writeFile(dir_.path() / "base.yaml", kManifestScene); }
  Manifest parse(const std::string& text) {
    test::writeFile(dir_.path() / "m.yaml", text);
    return loadManifest(dir_.path() / "m.yaml");
  }
  ResolvedItem resolve(const Manifest& m, std::size_t i) { return resolveItem(m, m.items[i], ""); }
  std::string value(const ResolvedItem& r, const std::string& path) {
    for (const auto& [p, v] : r.parameters)
      if (p == path) return v;
    return "<unset>";
  }
  test::TempDir dir_;
};

TEST_F(ManifestTest, SetItemsGridAndDrawsResolveInTheDocumentedOrder) {
  const Manifest m = parse(
      "format: camsim-dataset/1\nscene: base.yaml\nseed: 5\n"
      "set: {render.spp: 2}\n"
      "items:\n  - {camera.f_number: 2}\n  - {camera.f_number: 11, 'shapes[ball].radius': 0.5}\n"
      "grid:\n  camera.f_number: [4, 8]\n  shapes[1].corner: [[-2, -1, -2], [-3, -1, -3], [-4, -1, "
      "-4]]\n"
      "random:\n  count: 2\n  draw:\n    shapes[ball].emission.luminance: {uniform: [10, 20]}\n");
  ASSERT_EQ(m.items.size(), 2u + 2u * 3u * 2u);
  const ResolvedItem a = resolve(m, 1);
  EXPECT_EQ(a.description.camera.fNumber, 11.0);
  EXPECT_EQ(a.description.render.spp, 2);
  EXPECT_EQ(value(a, "shapes[ball].radius"), "0.5");
  // Grid cells: f-number slowest; each cell twice (random.count).
  const std::vector<std::pair<double, std::string>> expected = {
      {4, "[-2, -1, -2]"}, {4, "[-3, -1, -3]"}, {4, "[-4, -1, -4]"},
      {8, "[-2, -1, -2]"}, {8, "[-3, -1, -3]"}, {8, "[-4, -1, -4]"}};
  for (std::size_t c = 0; c < expected.size(); ++c)
    for (std::size_t r = 0; r < 2; ++r) {
      const ResolvedItem item = resolve(m, 2 + 2 * c + r);
      EXPECT_EQ(item.description.camera.fNumber, expected[c].first) << item.index;
      EXPECT_EQ(value(item, "shapes[1].corner"), expected[c].second) << item.index;
      const double lum = std::stod(value(item, "shapes[ball].emission.luminance"));
      EXPECT_GE(lum, 10.0);
      EXPECT_LE(lum, 20.0);
    }
  // The two draws of one cell differ; every item has its own render seed.
  EXPECT_NE(value(resolve(m, 2), "shapes[ball].emission.luminance"),
            value(resolve(m, 3), "shapes[ball].emission.luminance"));
  EXPECT_NE(resolve(m, 2).description.render.seed, resolve(m, 3).description.render.seed);
}

TEST_F(ManifestTest, AnItemDependsOnlyOnTheDatasetSeedAndItsIndex) {
  const std::string body =
      "scene: base.yaml\nrandom:\n  count: 6\n  draw:\n"
      "    camera.f_number: {log_uniform: [1.4, 16]}\n"
      "    shapes[ball].radius: {normal: {mean: 1, sd: 0.2, min: 0.8, max: 1.1}}\n"
      "    shapes[0].emission.luminance: {choice: [1, 10, 100]}\n";
  const Manifest a = parse("format: camsim-dataset/1\nseed: 1\n" + body);
  const Manifest b = parse("format: camsim-dataset/1\nseed: 1\n" + body);
  const Manifest c = parse("format: camsim-dataset/1\nseed: 2\n" + body);
  int differing = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const ResolvedItem ra = resolve(a, i), rb = resolve(b, i), rc = resolve(c, i);
    EXPECT_EQ(ra.sceneText, rb.sceneText);
    EXPECT_EQ(ra.hash, rb.hash);
    differing += ra.sceneText != rc.sceneText;
    const double f = ra.description.camera.fNumber, r = std::stod(value(ra, "shapes[ball].radius"));
    EXPECT_GE(f, 1.4);
    EXPECT_LE(f, 16.0);
    EXPECT_GE(r, 0.8);
    EXPECT_LE(r, 1.1);
  }
  EXPECT_EQ(differing, 6);
  // Item 4 of a longer run is item 4 of this one: draws do not depend on the count.
  std::string longer = body;
  longer.replace(longer.find("count: 6"), 8, "count: 9");
  EXPECT_EQ(resolve(parse("format: camsim-dataset/1\nseed: 1\n" + longer), 4).sceneText,
            resolve(a, 4).sceneText);
}

// Per-item seeds survive an edit that replaces the whole render map or adds the sensor
// (found by probing: `set: {render: {spp: 2}}` rendered every item with seed 0 while
// params.json listed the seeds); an item's own seed, by its key or in its map, wins.
TEST_F(ManifestTest, PerItemSeedsSurviveAReplacedRenderOrSensorMap) {
  const Manifest m = parse(
      "format: camsim-dataset/1\nscene: base.yaml\nseed: 5\n"
      "set: {render: {spp: 2}, sensor: {model: smartphone-1.4um}}\n"
      "items:\n  - {}\n  - {}\n  - {render: {spp: 2, seed: 7}, sensor.noise_seed: 9}\n");
  const ResolvedItem a = resolve(m, 0), b = resolve(m, 1), c = resolve(m, 2);
  EXPECT_EQ(a.description.render.spp, 2);
  EXPECT_NE(a.description.render.seed, 0u);
  EXPECT_NE(a.description.render.seed, b.description.render.seed);
  ASSERT_TRUE(a.description.sensor && b.description.sensor);
  EXPECT_NE(a.description.sensor->noiseSeed, 0u);
  EXPECT_NE(a.description.sensor->noiseSeed, b.description.sensor->noiseSeed);
  EXPECT_EQ(value(a, "render.seed"), std::to_string(a.description.render.seed));
  EXPECT_EQ(value(a, "sensor.noise_seed"), std::to_string(a.description.sensor->noiseSeed));
  EXPECT_EQ(c.description.render.seed, 7u);
  EXPECT_EQ(c.description.sensor->noiseSeed, 9u);
  // The last edit decides: an item's sensor map without a seed drops the set's seed 9, and
  // the item gets its own (found in review).
  const Manifest n = parse(
      "format: camsim-dataset/1\nscene: base.yaml\nseed: 5\n"
      "set: {sensor: {model: smartphone-1.4um, noise_seed: 9}}\n"
      "items:\n  - {sensor: {model: smartphone-1.4um}}\n  - {}\n");
  const ResolvedItem replaced = resolve(n, 0), kept = resolve(n, 1);
  ASSERT_TRUE(replaced.description.sensor && kept.description.sensor);
  EXPECT_NE(replaced.description.sensor->noiseSeed, 9u);
  EXPECT_NE(replaced.description.sensor->noiseSeed, 0u);
  EXPECT_EQ(kept.description.sensor->noiseSeed, 9u);
}

TEST_F(ManifestTest, OrbitZippedKeysAndNull) {
  const Manifest m = parse(
      "format: camsim-dataset/1\nscene: base.yaml\nseeds: fixed\n"
      "set: {camera.f_number: null}\n"
      "random:\n  count: 4\n  draw:\n"
      "    camera.position: {orbit: {centre: [0, 0.5, 0], radius: [2, 3], azimuth_deg: [-30, 30], "
      "elevation_deg: [0, 20]}}\n"
      "    'camera.f_number, render.spp': {choice: [[2, 3], [8, 5]]}\n");
  for (std::size_t i = 0; i < 4; ++i) {
    const ResolvedItem r = resolve(m, i);
    const glm::dvec3 p = r.description.renderOrigin;  // the camera sits at the render origin
    const double distance = glm::length(p - glm::dvec3(0, 0.5, 0));
    EXPECT_GE(distance, 2.0 - 1e-9);
    EXPECT_LE(distance, 3.0 + 1e-9);
    EXPECT_LE(p.z, 0.0);  // azimuth within ±30° of the −z side
    EXPECT_GE(p.y, 0.5 - 1e-9);
    const bool pairA = r.description.camera.fNumber == 2 && r.description.render.spp == 3;
    const bool pairB = r.description.camera.fNumber == 8 && r.description.render.spp == 5;
    EXPECT_TRUE(pairA || pairB) << r.sceneText;
    EXPECT_EQ(r.description.render.seed, 0u);  // seeds: fixed keeps the scene's
  }
  const Manifest n =
      parse("format: camsim-dataset/1\nscene: base.yaml\nitems: [{camera.f_number: null}]\n");
  EXPECT_EQ(resolve(n, 0).sceneText.find("f_number"), std::string::npos);
}

struct BadManifest {
  const char* name;
  const char* body;  // after "format: camsim-dataset/1\nscene: base.yaml\n"
  int line;          // of the manifest, as the message names it
  const char* key;
  const char* words;  // in the message
};

class MalformedManifest : public ManifestTest, public testing::WithParamInterface<BadManifest> {};

TEST_P(MalformedManifest, IsRejectedWithTheManifestsLineAndKey) {
  const BadManifest& c = GetParam();
  try {
    const Manifest m = parse(std::string("format: camsim-dataset/1\nscene: base.yaml\n") + c.body);
    checkBaseScene(m);
    for (const DatasetItem& item : m.items) (void)resolveItem(m, item, "");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, (dir_.path() / "m.yaml").string()) << e.what();
    EXPECT_EQ(e.where().line, c.line) << e.what();
    EXPECT_NE(e.key().find(c.key), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.words), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedManifest,
    testing::Values(
        BadManifest{"UnknownKeyPath", "items:\n  - {camera.f_numbr: 2}\n", 4, "camera.f_numbr",
                    "unknown key"},
        BadManifest{"ImpossibleValue", "grid:\n  camera.f_number: [2, -1]\n", 4,
                    "grid.camera.f_number", "item 1"},
        BadManifest{"NoSuchShapeName", "items:\n  - {'shapes[lamp].radius': 2}\n", 4,
                    "shapes[lamp].radius", "no element named 'lamp'"},
        BadManifest{"IndexPastTheEnd", "items:\n  - {'shapes[7].radius': 2}\n", 4,
                    "shapes[7].radius", "past the end"},
        BadManifest{"MalformedPath", "items:\n  - {camera..f_number: 2}\n", 4, "camera..f_number",
                    "malformed key path"},
        BadManifest{"EmptyRange", "random:\n  draw:\n    camera.f_number: {uniform: [4, 2]}\n", 5,
                    "random.draw.camera.f_number", "lo <= hi"},
        BadManifest{"UnknownDraw", "random:\n  draw:\n    camera.f_number: {gaussian: [4, 2]}\n", 5,
                    "random.draw.camera.f_number", "unknown draw 'gaussian'"},
        BadManifest{"NegativeLogRange",
                    "random:\n  draw:\n    camera.f_number: {log_uniform: [0, 2]}\n", 5,
                    "random.draw.camera.f_number", "a log-uniform range must be positive"},
        // The orbit's radius is drawn uniformly (found by probing: its error
        // called it a log-uniform range).
        BadManifest{"ZeroOrbitRadius",
                    "random:\n  draw:\n    camera.position: {orbit: {centre: [0, 0, 0], "
                    "radius: [0, 1]}}\n",
                    5, "random.draw.camera.position.orbit.radius",
                    "an orbit's radius range (m) must be positive"},
        BadManifest{"ZippedValueOfWrongLength",
                    "grid:\n  'camera.f_number, render.spp': [[2, 4], [8]]\n", 4,
                    "grid.camera.f_number, render.spp", "a list of 2 values"},
        BadManifest{"UnknownTopLevelKey", "grids:\n  camera.f_number: [2]\n", 3, "grids",
                    "unknown key"}),
    [](const testing::TestParamInfo<BadManifest>& p) { return std::string(p.param.name); });

TEST_F(ManifestTest, AManifestWithoutItemsOrAMissingSceneIsAnError) {
  EXPECT_THROW(parse("format: camsim-dataset/1\nscene: base.yaml\n"), InputError);
  try {
    parse("format: camsim-dataset/1\nscene: nowhere.yaml\nitems: [{}]\n");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 2) << e.what();
    EXPECT_NE(std::string(e.what()).find("nowhere.yaml"), std::string::npos) << e.what();
  }
}

// Every dataset manifest shipped in scenes/ resolves, every item loading.
TEST(ExampleManifests, EveryShippedManifestResolves) {
  int manifests = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(CAMSIM_SOURCE_DIR) / "scenes")) {
    if (e.path().extension() != ".yaml" ||
        test::readFile(e.path()).find("format: camsim-dataset/1") == std::string::npos)
      continue;
    ++manifests;
    const Manifest m = loadManifest(e.path());
    checkBaseScene(m);
    EXPECT_GE(m.items.size(), 1u) << e.path();
    for (const DatasetItem& item : m.items)
      EXPECT_NO_THROW((void)resolveItem(m, item, "")) << e.path();
  }
  EXPECT_GE(manifests, 1);
}

}  // namespace
}  // namespace camsim
