// ID mattes (integrator/render/id_film.h, cryptomatte.h): the Cryptomatte hash against the
// specification's own examples; coverage at a motion-blurred edge and at a defocused edge
// against the analytic ramp (the pixel box convolved with the edge's sweep or the lens
// disc) within 2 %; coverages summing to 1; the dominant id and the class numbering.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "integrator/render/cryptomatte.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_ids.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/support/scene_text.h"

namespace camsim {
namespace {

using test::num;

// The manifest example of the Cryptomatte specification 1.1.0 (its "bunny" and "default"
// names and their hex ids).
TEST(Cryptomatte, IdsMatchTheSpecificationsManifest) {
  EXPECT_EQ(cryptomatteHex(cryptomatteId("bunny")), "13851a76");
  EXPECT_EQ(cryptomatteHex(cryptomatteId("default")), "42c9679f");
  EXPECT_EQ(cryptomatteHex(cryptomatteId("bunny_porcelain_mat")), "b24b26d4");
  EXPECT_EQ(cryptomatteId(""), 0.0f);
  EXPECT_EQ(cryptomatteKey("CryptoObject").size(), 7u);
  const Metadata m = cryptomatteMetadata("CryptoObject", {"", "bunny", "bunny"});
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[0].first, "cryptomatte/" + cryptomatteKey("CryptoObject") + "/name");
  EXPECT_EQ(m[1].second, "MurmurHash3_32");
  EXPECT_EQ(m[2].second, "uint32_to_float32");
  EXPECT_NE(m[3].second.find("\"bunny\": \"13851a76\""), std::string::npos) << m[3].second;
}

// Ids avoid the float exponents 0 and 255 (no zero, denormal, inf, NaN) for any name.
TEST(Cryptomatte, IdsAreNormalFloats) {
  for (int i = 0; i < 20000; ++i) {
    const float id = cryptomatteId("object_" + std::to_string(i));
    ASSERT_TRUE(std::isnormal(id)) << i;
  }
}

constexpr int kMatteW = 48, kMatteH = 4;

// A card (the instance "card", class "target") whose edge crosses the image vertically, in
// front of a wall, looking along −z (image right is world +x). `camera` adds to the camera
// block, `card` to the card's shape.
SceneDescription edgeScene(const std::string& camera, const std::string& card,
                           const std::string& extra = "") {
  const std::string text =
      "camera: {position: [0, 0, 0], look_at: [0, 0, -1], up: [0, 1, 0], resolution: [" +
      std::to_string(kMatteW) + ", " + std::to_string(kMatteH) +
      "], sensor_width_mm: 6, sensor_height_mm: 0.5, focal_length_mm: 20" + camera +
      "}\n"
      "render: {spp: 1024, max_depth: 1, aovs: [instance_id, class_id, material_id]}\n" +
      extra +
      "materials: {grey: {type: diffuse, reflectance: 0.5}, paper: {type: diffuse, "
      "reflectance: 0.8}}\n"
      "shapes:\n"
      "  - {name: wall, type: rectangle, corner: [-50, -50, -20], edge_u: [100, 0, 0], "
      "edge_v: [0, 100, 0], material: grey}\n"
      "  - {name: card, class: target, type: rectangle, corner: [-10, -10, -0.25], edge_u: [10, "
      "0, 0], edge_v: [0, 20, 0], material: paper" +
      card +
      "}\n"
      "lights:\n  - {type: point, position: [0, 0, 0], intensity: 1}\n";
  return loadSceneFromText(text, "edge.yaml", ".");
}

Image renderIds(const SceneDescription& d) {
  RenderOptions o;
  o.spp = d.render.spp;
  return render(Scene(d), SpectralResponse::cieXyz(), o).aovs;
}

// The coverage of the id `id` in pixel (x, y) of a Cryptomatte type, summed over its ranks.
double coverageOf(const Image& a, const std::string& type, float id, int x, int y) {
  double c = 0.0;
  for (const char* layer : {"00", "01", "02"})
    for (const char* pair : {"RG", "BA"}) {
      const std::string base = type + layer + ".";
      if (a.at(x, y, a.channelIndex(base + pair[0])) == id)
        c += static_cast<double>(a.at(x, y, a.channelIndex(base + pair[1])));
    }
  return c;
}

double sumOfCoverages(const Image& a, const std::string& type, int x, int y) {
  double c = 0.0;
  for (const char* layer : {"00", "01", "02"})
    for (const char* cov : {".G", ".A"})
      c += static_cast<double>(a.at(x, y, a.channelIndex(type + layer + cov)));
  return c;
}

// The card's edge x = 0 at 0.25 m images at OpenCV column cx (pixel centres at integers);
// the card covers the image's left (world x < 0).
constexpr double kMattePitch = 0.006 / kMatteW, kMatteFocal = 0.02, kCard = 0.25;
constexpr double kCx = 0.5 * kMatteW - 0.5;

// The card moving +x by 1.5 cm during the shutter at 0.25 m: its edge sweeps
// 1.5 cm · f / (z · pitch) = 9.6 px linearly in time; the card covers pixel x for the
// fraction of (time × pixel box) in which the edge is right of the point.
TEST(IdMattes, MotionBlurredEdgeFollowsTheLinearRamp) {
  const double sweep = 0.015;  // m during the shutter
  const SceneDescription d =
      edgeScene(", shutter: {open: 0, close: 0.01}",
                ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.01, translate: [" +
                    num(sweep) + ", 0, 0]}]");
  const Image a = renderIds(d);
  const float card = cryptomatteId("card"), wall = cryptomatteId("wall");
  const double e0 = kCx, e1 = kCx + sweep * kMatteFocal / (kCard * kMattePitch);  // edge column, px
  ASSERT_GT(e1 - e0, 8.0);
  double worst = 0.0;
  for (int x = 0; x < kMatteW; ++x) {
    // Mean over time and over the pixel box [x − ½, x + ½] of [u < e(t)].
    double expected = 0.0;
    constexpr int kN = 400;
    for (int i = 0; i < kN; ++i) {
      const double e = e0 + (e1 - e0) * (i + 0.5) / kN;
      expected += std::clamp(e - (x - 0.5), 0.0, 1.0);
    }
    expected /= kN;
    for (int y = 0; y < kMatteH; ++y) {
      const double c = coverageOf(a, "CryptoObject", card, x, y);
      worst = std::max(worst, std::abs(c - expected));
      ASSERT_NEAR(c, expected, 0.02) << "x " << x << " y " << y;
      ASSERT_NEAR(sumOfCoverages(a, "CryptoObject", x, y), 1.0, 1e-6);
      ASSERT_NEAR(coverageOf(a, "CryptoObject", wall, x, y), 1.0 - c, 1e-6);
      // The class matte follows the card; the wall has no class (id 0).
      ASSERT_NEAR(coverageOf(a, "CryptoClass", cryptomatteId("target"), x, y), c, 1e-6);
      ASSERT_NEAR(coverageOf(a, "CryptoMaterial", cryptomatteId("paper"), x, y), c, 1e-6);
    }
  }
  RecordProperty("worst_coverage_error", std::to_string(worst));
  std::printf("motion-blurred edge: worst coverage error %.4f\n", worst);
  // The dominant id: the card (instance 2, class 1) left of the ramp, the wall right of it.
  EXPECT_EQ(a.at(0, 0, a.channelIndex("instance.id")), 2.0f);
  EXPECT_EQ(a.at(0, 0, a.channelIndex("class.id")), 1.0f);
  EXPECT_EQ(a.at(0, 0, a.channelIndex("material.id")), 2.0f);
  EXPECT_EQ(a.at(kMatteW - 1, 0, a.channelIndex("instance.id")), 1.0f);
  EXPECT_EQ(a.at(kMatteW - 1, 0, a.channelIndex("class.id")), 0.0f);
}

// Unit disc's area fraction with x < u.
double discFraction(double u) {
  if (u <= -1.0) return 0.0;
  if (u >= 1.0) return 1.0;
  return 1.0 - (std::acos(u) - u * std::sqrt(1.0 - u * u)) / M_PI;
}

// f/1 focused at infinity: the card's edge at 0.25 m is blurred by the lens disc, radius
// (D/2)·f/z = 6.4 px on the film; the card covers a film point for the fraction of the
// disc (the rays of that film point meet the card plane in a disc) on its side.
TEST(IdMattes, DefocusedEdgeFollowsTheDiscOverlap) {
  const SceneDescription d = edgeScene(", f_number: 1, aperture: {blades: 0}", "");
  const Image a = renderIds(d);
  const float card = cryptomatteId("card");
  const double radiusPx = 0.5 * (kMatteFocal / 1.0) * kMatteFocal / kCard / kMattePitch;
  ASSERT_GT(radiusPx, 3.0);
  for (int x = 0; x < kMatteW; ++x) {
    double expected = 0.0;
    constexpr int kN = 400;
    for (int i = 0; i < kN; ++i) {
      const double u = x - 0.5 + (i + 0.5) / kN;  // film column, px
      expected += discFraction((kCx - u) / radiusPx);
    }
    expected /= kN;
    for (int y = 0; y < kMatteH; ++y) {
      ASSERT_NEAR(coverageOf(a, "CryptoObject", card, x, y), expected, 0.02)
          << "x " << x << " y " << y;
      ASSERT_NEAR(sumOfCoverages(a, "CryptoObject", x, y), 1.0, 1e-6);
    }
  }
}

// Misses are id 0 (nothing) and count: coverages still sum to 1.
TEST(IdMattes, MissesAreIdZeroAndCoveragesSumToOne) {
  SceneDescription d = edgeScene("", "");
  d.shapes.erase(d.shapes.begin());  // no wall: the right half sees nothing
  const Image a = renderIds(d);
  EXPECT_EQ(a.at(kMatteW - 1, 0, a.channelIndex("CryptoObject00.R")), 0.0f);
  EXPECT_EQ(a.at(kMatteW - 1, 0, a.channelIndex("CryptoObject00.G")), 1.0f);
  EXPECT_EQ(a.at(kMatteW - 1, 0, a.channelIndex("instance.id")), 0.0f);
  for (int x = 0; x < kMatteW; ++x) EXPECT_NEAR(sumOfCoverages(a, "CryptoObject", x, 1), 1.0, 1e-6);
}

// class: integers are their own numbers; names are numbered after the largest integer in
// order of first use; unlabelled shapes are 0.
TEST(IdMattes, ClassNumbering) {
  const std::string text =
      "camera: {position: [0, 0, 0], look_at: [0, 0, -1]}\n"
      "materials: {m: {type: diffuse, reflectance: 0.5}}\n"
      "shapes:\n"
      "  - {type: sphere, centre: [0, 0, -5], radius: 1, material: m, class: car}\n"
      "  - {type: sphere, centre: [3, 0, -5], radius: 1, material: m, class: 7}\n"
      "  - {type: sphere, centre: [-3, 0, -5], radius: 1, material: m}\n"
      "  - {type: sphere, centre: [0, 3, -5], radius: 1, material: m, class: person}\n"
      "  - {type: sphere, centre: [0, -3, -5], radius: 1, material: m, class: car}\n";
  const SceneIds ids = sceneIds(loadSceneFromText(text, "c.yaml", "."));
  const IdTable& c = ids[IdKind::kClass];
  EXPECT_EQ(c.ofShape, (std::vector<std::uint32_t>{1, 2, 0, 3, 1}));
  EXPECT_EQ(c.numbers, (std::vector<std::uint32_t>{0, 8, 7, 9}));
  EXPECT_EQ(c.names[1], "car");
  EXPECT_EQ(ids[IdKind::kInstance].names[3], "shapes[2]");
  for (const char* bad : {"0", "-2", "''"}) {
    const std::string t =
        "camera: {position: [0, 0, 0], look_at: [0, 0, -1]}\n"
        "materials: {m: {type: diffuse, reflectance: 0.5}}\n"
        "shapes:\n  - {type: sphere, centre: [0, 0, -5], radius: 1, "
        "material: m, class: " +
        std::string(bad) + "}\n";
    try {
      loadSceneFromText(t, "bad.yaml", ".");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("class"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace camsim
