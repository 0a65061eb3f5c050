// Occlusion-aware flow and occlusion boundaries (aovs occlusion, boundary;
// integrator/render/occlusion_film.h) against exact geometry: the crescents a ball moving
// across a wall uncovers and covers, against the analytic areas; no occlusion at all where
// none can happen (a camera turning about its centre before a ball, a wall and a tilted
// plane; a camera moving inside a room and inside a sphere); the boundary layer against
// each pixel's analytic footprint; threads and the other AOVs unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <glm/trigonometric.hpp>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/support/render_frame.h"
#include "tests/support/scene_text.h"

namespace camsim {
namespace occlusion_film_test {

using test::num;

constexpr int kRes = 96;
// fx = f / pitch = 50 mm / (24 mm / 96) px; the principal point at the image centre.
constexpr double kF = 50.0 / (24.0 / kRes), kC = 0.5 * kRes - 0.5;

// 96 × 96 pinhole at the origin looking along −z (+y up: image right is world +x, image
// down world −y); frames at 10 Hz with a 0.036° shutter (10 µs: no motion blur to speak of).
SceneDescription scene(const std::string& shapes, const std::string& camera,
                       const std::string& aovs, int spp = 64) {
  const std::string text =
      "camera: {position: [0, 0, 0], look_at: [0, 0, -1], up: [0, 1, 0], resolution: [" +
      std::to_string(kRes) + ", " + std::to_string(kRes) +
      "], sensor_width_mm: 24, sensor_height_mm: 24, focal_length_mm: 50" + camera +
      "}\n"
      "render: {spp: " +
      std::to_string(spp) + ", max_depth: 1, aovs: " + aovs +
      "}\n"
      "frames: {count: 3, rate_hz: 10, shutter_angle_deg: 0.036}\n"
      "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
      "shapes:\n" +
      shapes + "lights:\n  - {type: point, position: [0, 0, 0], intensity: 1}\n";
  return loadSceneFromText(text, "occlusion.yaml", ".");
}

double value(const Image& im, int x, int y, const char* channel) {
  return static_cast<double>(im.at(x, y, im.channelIndex(channel)));
}
double sum(const Image& im, const char* channel) {
  double s = 0.0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) s += value(im, x, y, channel);
  return s;
}

// The area (px²) of {(u, v) : inside(u, v)} within [u0, u1] × [v0, v1] (OpenCV pixel
// coordinates): rows by the midpoint rule (step h), each row's set exactly up to 1e-9 px
// from its changes, found every `scan` px and bisected. Sets thinner than `scan` that do
// not touch a change of the rest are missed; the sets here have no such parts.
double areaOf(const std::function<bool(double, double)>& inside, double u0, double u1, double v0,
              double v1, double h, double scan = 0.25) {
  double area = 0.0;
  const int rows = static_cast<int>(std::ceil((v1 - v0) / h));
  const int cols = static_cast<int>(std::ceil((u1 - u0) / scan));
  for (int r = 0; r < rows; ++r) {
    const double v = v0 + (r + 0.5) * (v1 - v0) / rows;
    bool prev = inside(u0, v);
    double start = u0, length = 0.0;  // start: where the current run inside began
    for (int c = 1; c <= cols; ++c) {
      const double u = u0 + c * (u1 - u0) / cols;
      const bool now = inside(u, v);
      if (now == prev) continue;
      double lo = u0 + (c - 1) * (u1 - u0) / cols, hi = u;  // bisect the change
      while (hi - lo > 1e-9) {
        const double mid = 0.5 * (lo + hi);
        (inside(mid, v) == prev ? lo : hi) = mid;
      }
      const double edge = 0.5 * (lo + hi);
      if (prev)
        length += edge - start;
      else
        start = edge;
      prev = now;
    }
    if (prev) length += u1 - start;
    area += length * (v1 - v0) / rows;
  }
  return area;
}

// The camera ray through pixel coordinates (u, v): direction (a, −b, −1), world axes.
glm::dvec3 rayThrough(double u, double v) {
  return {(u - kC) / kF, -(v - kC) / kF, -1.0};
}
// Nearest t > 0 with |t d − s| = r (d from the origin), or −1.
double sphereHit(const glm::dvec3& d, const glm::dvec3& s, double r) {
  const double dd = glm::dot(d, d), ds = glm::dot(d, s),
               disc = ds * ds - dd * (glm::dot(s, s) - r * r);
  if (disc < 0.0) return -1.0;
  const double t = (ds - std::sqrt(disc)) / dd;
  return t > 0.0 ? t : -1.0;
}

// A ball of radius 0.25 m at 2.5 m before a wall at 5 m, moving +x at 1 m/s: 0.1 m per
// frame, ≈ 8 px. At frame 1 it is on the axis. Of the wall's points seen at frame 1, those
// the ball covers at frame 2 (the crescent ahead of it) are occluded forward, those it
// covered at frame 0 (the one behind it) backward; and of the ball's own points, a sliver
// at its leading (trailing) limb turns away from the camera by frame 2 (0). The reference:
// for every image point of frame 1 the exact ray–sphere and ray–plane hits at frames 1 and
// 1 ± 1, integrated over the image (areaOf).
TEST(OcclusionFilm, BallCrescentAreasMatchTheAnalyticReference) {
  const double r = 0.25, z = -2.5;
  const SceneDescription d = scene(
      "  - {name: wall, type: rectangle, corner: [-5, -5, -5], edge_u: [10, 0, 0], "
      "edge_v: [0, 10, 0], material: grey}\n"
      "  - {name: ball, type: sphere, centre: [-0.1, 0, " +
          num(z) + "], radius: " + num(r) +
          ", material: grey, motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, "
          "translate: [1, 0, 0]}]}\n",
      "", "[occlusion]");
  const Image a = test::renderSequenceFrame(d, 1).aovs;
  // The ball's centre at each frame's reference time (the shutter's centre).
  const auto centreAt = [&](int k) {
    return glm::dvec3(-0.1 + d.frameCamera(k).shutter.centre(), 0.0, z);
  };
  const glm::dvec3 s1 = centreAt(1);
  // Whether the frame-1 point at (u, v) is hidden at frame k (the camera does not move).
  const auto hiddenAt = [&](int k, double u, double v) {
    const glm::dvec3 dir = rayThrough(u, v), sk = centreAt(k);
    const double t = sphereHit(dir, s1, r);
    if (t < 0.0) return sphereHit(dir, sk, r) > 0.0;  // a wall point behind the ball at k
    // A ball point, moved with the ball: hidden if it faces away from the camera at k.
    const glm::dvec3 x = t * dir + (sk - s1);
    return glm::dot(x - sk, -x) < 0.0;
  };
  const double lo = kC - 32.0, hi = kC + 32.0;  // the ball's images: 20 px in radius, 8 px apart
  const double fw =
      areaOf([&](double u, double v) { return hiddenAt(2, u, v); }, lo, hi, lo, hi, 0.02);
  const double bw =
      areaOf([&](double u, double v) { return hiddenAt(0, u, v); }, lo, hi, lo, hi, 0.02);
  const double renderedFw = sum(a, "occlusion_fw.A"), renderedBw = sum(a, "occlusion_bw.A");
  std::printf(
      "crescent ahead: %.3f px² rendered, %.3f px² exact (%+.3f %%); behind: %.3f, "
      "%.3f (%+.3f %%)\n",
      renderedFw, fw, 100.0 * (renderedFw / fw - 1.0), renderedBw, bw,
      100.0 * (renderedBw / bw - 1.0));
  EXPECT_GT(fw, 200.0);  // ≈ 2 ρ δ = 2 · 20 · 8 px²
  EXPECT_NEAR(renderedFw, fw, 0.01 * fw);
  EXPECT_NEAR(renderedBw, bw, 0.01 * bw);
  EXPECT_EQ(sum(a, "outside_fw.A"), 0.0);  // everything stays in view
  EXPECT_EQ(sum(a, "outside_bw.A"), 0.0);
  // Ahead of the ball forward, behind it backward, nothing elsewhere (x: columns).
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      if (x < kC) {
        ASSERT_EQ(value(a, x, y, "occlusion_fw.A"), 0.0) << x << "," << y;
      } else {
        ASSERT_EQ(value(a, x, y, "occlusion_bw.A"), 0.0) << x << "," << y;
      }
    }
}

// Whether image point q lies inside the convex quad c (corners in order, either turn).
bool insideQuad(const std::array<glm::dvec2, 4>& c, glm::dvec2 q) {
  int sign = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    const glm::dvec2 e = c[(i + 1) % 4] - c[i], w = q - c[i];
    const int s = e.x * w.y - e.y * w.x > 0.0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

// The keyframed copies of meshes (occlusion_film.cpp: a baked rectangle and an instanced
// mesh take other paths than a sphere): a card (rectangle) sliding +x at 2.5 m and an
// instance of a square mesh sliding −x and spinning 10° per frame about the optical axis at
// 3 m (another, static instance of the mesh makes it instanced), before a wall. Both stay
// fronto-parallel, so each image is the exact projected quad: forward, the wall points of
// frame 1 inside a card's quad at frame 2 and outside it at frame 1; backward, frame 0's.
TEST(OcclusionFilm, MovingMeshesCoverTheExactArea) {
  const SceneDescription d = scene(
      "  - {name: wall, type: rectangle, corner: [-5, -5, -5], edge_u: [10, 0, 0], "
      "edge_v: [0, 10, 0], material: grey}\n"
      "  - {name: card, type: rectangle, corner: [-0.5, 0.05, -2.5], edge_u: [0.3, 0, 0], "
      "edge_v: [0, 0.3, 0], material: grey, motion: [{time: 0, translate: [0, 0, 0]}, "
      "{time: 1, translate: [1, 0, 0]}]}\n"
      "  - type: mesh\n"
      "    material: grey\n"
      "    vertices: [[-0.15, -0.15, 0], [0.15, -0.15, 0], [0.15, 0.15, 0], [-0.15, 0.15, 0]]\n"
      "    faces: [[0, 1, 2], [0, 2, 3]]\n"
      "    instances:\n"
      "      - {translate: [0.3, 0.3, -4]}\n"
      "      - {motion: [{time: 0, translate: [0.35, -0.3, -3], rotate: {axis: [0, 0, 1], "
      "angle_deg: 0}}, {time: 1, translate: [-0.65, -0.3, -3], rotate: {axis: [0, 0, 1], "
      "angle_deg: 100}}]}\n",
      "", "[occlusion]");
  const Image a = test::renderSequenceFrame(d, 1).aovs;
  // The moving cards' image quads at frame k.
  const auto project = [](const glm::dvec3& p) {
    return glm::dvec2(kC + kF * p.x / -p.z, kC - kF * p.y / -p.z);
  };
  const auto quadsAt = [&](int k) {
    const double t = d.frameCamera(k).shutter.centre(), th = glm::radians(100.0 * t);
    std::array<std::array<glm::dvec2, 4>, 2> q;
    const double card[4][2] = {{-0.5, 0.05}, {-0.2, 0.05}, {-0.2, 0.35}, {-0.5, 0.35}};
    const double square[4][2] = {{-0.15, -0.15}, {0.15, -0.15}, {0.15, 0.15}, {-0.15, 0.15}};
    for (std::size_t i = 0; i < 4; ++i) {
      q[0][i] = project({card[i][0] + t, card[i][1], -2.5});
      const double x = square[i][0], y = square[i][1];
      q[1][i] = project({0.35 - t + std::cos(th) * x - std::sin(th) * y,
                         -0.3 + std::sin(th) * x + std::cos(th) * y, -3.0});
    }
    return q;
  };
  const auto q1 = quadsAt(1);
  const auto hiddenAt = [&](const std::array<std::array<glm::dvec2, 4>, 2>& qk, double u,
                            double v) {
    const glm::dvec2 p(u, v);
    if (insideQuad(q1[0], p) || insideQuad(q1[1], p)) return false;  // a card: stays in view
    return insideQuad(qk[0], p) || insideQuad(qk[1], p);
  };
  const auto q0 = quadsAt(0), q2 = quadsAt(2);
  const double e = kRes - 0.5;
  const double fw =
      areaOf([&](double u, double v) { return hiddenAt(q2, u, v); }, -0.5, e, -0.5, e, 0.02);
  const double bw =
      areaOf([&](double u, double v) { return hiddenAt(q0, u, v); }, -0.5, e, -0.5, e, 0.02);
  const double renderedFw = sum(a, "occlusion_fw.A"), renderedBw = sum(a, "occlusion_bw.A");
  std::printf("moving meshes: %.3f / %.3f px² rendered, %.3f / %.3f exact\n", renderedFw,
              renderedBw, fw, bw);
  EXPECT_GT(fw, 250.0);  // the card's 8 × 24 px strip and the square's swept edges
  EXPECT_NEAR(renderedFw, fw, 0.01 * fw);
  EXPECT_NEAR(renderedBw, bw, 0.01 * bw);
  EXPECT_EQ(sum(a, "outside_fw.A") + sum(a, "outside_bw.A"), 0.0);
}

// A static ball, wall and tilted plane; the camera turns about its own centre (4° about a
// tilted axis per frame): every point seen stays visible from the same centre, so no sample
// may be occluded. Points turn out of the image at the edges: outside_* against the exact
// area of frame 1's image that the camera at frame 0 / 2 does not image inside its own.
TEST(OcclusionFilm, CameraTurningAboutItsCentreOccludesNothing) {
  const SceneDescription d = scene(
      "  - {name: wall, type: rectangle, corner: [-20, -20, -6], edge_u: [40, 0, 0], edge_v: "
      "[0, 40, -8], material: grey}\n"
      "  - {name: ball, type: sphere, centre: [0.2, -0.1, -3], radius: 0.4, material: grey}\n"
      "  - {name: card, type: rectangle, corner: [-0.6, -0.5, -2], edge_u: [0.8, 0, -0.4], "
      "edge_v: [0, 0.7, 0.2], material: grey}\n",
      ", motion: [{time: 0, rotate: {axis: [0.3, 1, 0.2], angle_deg: 0}}, {time: 1, rotate: "
      "{axis: [0.3, 1, 0.2], angle_deg: 40}}]",
      "[occlusion, motion]", 16);
  const Image a = test::renderSequenceFrame(d, 1).aovs;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      ASSERT_EQ(value(a, x, y, "occlusion_fw.A"), 0.0) << x << "," << y;
      ASSERT_EQ(value(a, x, y, "occlusion_bw.A"), 0.0) << x << "," << y;
    }
  // The image of frame 1's direction (u, v) through the camera at frame k.
  const PhysicalCamera camera(d.frameCamera(1));
  const glm::dmat4 pose1 = camera.worldFromCameraAt(d.frameCamera(1).shutter.centre());
  const auto outsideAt = [&](int k, double u, double v) {
    const glm::dvec3 c((u - kC) / kF, (v - kC) / kF, 1.0);  // OpenCV camera axes
    const glm::dvec3 x = glm::dvec3(pose1[3]) + c.x * glm::dvec3(pose1[0]) -
                         c.y * glm::dvec3(pose1[1]) + c.z * glm::dvec3(pose1[2]);
    const std::optional<glm::dvec2> q = camera.project(x, d.frameCamera(k).shutter.centre());
    return !q || q->x < -0.5 || q->x >= kRes - 0.5 || q->y < -0.5 || q->y >= kRes - 0.5;
  };
  const double e = kRes - 0.5;
  const double fw =
      areaOf([&](double u, double v) { return outsideAt(2, u, v); }, -0.5, e, -0.5, e, 0.05, 1.0);
  const double bw =
      areaOf([&](double u, double v) { return outsideAt(0, u, v); }, -0.5, e, -0.5, e, 0.05, 1.0);
  const double renderedFw = sum(a, "outside_fw.A"), renderedBw = sum(a, "outside_bw.A");
  std::printf("turning camera: outside %.2f / %.2f px² (exact %.2f / %.2f), occluded 0\n",
              renderedFw, renderedBw, fw, bw);
  EXPECT_GT(fw, 500.0);
  EXPECT_NEAR(renderedFw, fw, 0.01 * fw);
  EXPECT_NEAR(renderedBw, bw, 0.01 * bw);
}

// From any point inside a convex room or a sphere, all of its inner surface is in view: a
// camera moving and turning inside them must see no sample occluded, only some leave the
// image.
TEST(OcclusionFilm, CameraMovingInsideConvexRoomsOccludesNothing) {
  const std::string cameraMotion =
      ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [3, 1, -5], rotate: "
      "{axis: [0, 1, 0.3], angle_deg: 60}}]";
  // A box x ∈ [−2, 2], y ∈ [−1.5, 1.5], z ∈ [−6, 1]: six rectangles.
  const std::string room =
      "  - {type: rectangle, corner: [-2, -1.5, -6], edge_u: [4, 0, 0], edge_v: [0, 3, 0], "
      "material: grey}\n"
      "  - {type: rectangle, corner: [-2, -1.5, 1], edge_u: [4, 0, 0], edge_v: [0, 3, 0], "
      "material: grey}\n"
      "  - {type: rectangle, corner: [-2, -1.5, -6], edge_u: [0, 0, 7], edge_v: [0, 3, 0], "
      "material: grey}\n"
      "  - {type: rectangle, corner: [2, -1.5, -6], edge_u: [0, 0, 7], edge_v: [0, 3, 0], "
      "material: grey}\n"
      "  - {type: rectangle, corner: [-2, -1.5, -6], edge_u: [4, 0, 0], edge_v: [0, 0, 7], "
      "material: grey}\n"
      "  - {type: rectangle, corner: [-2, 1.5, -6], edge_u: [4, 0, 0], edge_v: [0, 0, 7], "
      "material: grey}\n";
  const std::string sphere =
      "  - {type: sphere, centre: [0.3, 0, -0.5], radius: 3, material: grey}\n";
  for (const std::string& shapes : {room, sphere}) {
    const Image a =
        test::renderSequenceFrame(scene(shapes, cameraMotion, "[occlusion]", 16), 1).aovs;
    EXPECT_EQ(sum(a, "coverage.A"), kRes * kRes);  // every sample hits
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x) {
        ASSERT_EQ(value(a, x, y, "occlusion_fw.A"), 0.0) << x << "," << y;
        ASSERT_EQ(value(a, x, y, "occlusion_bw.A"), 0.0) << x << "," << y;
      }
    EXPECT_GT(sum(a, "outside_fw.A"), 100.0);
    EXPECT_GT(sum(a, "outside_bw.A"), 100.0);
  }
}

// The two new aovs leave every other channel and the image bit-identical, and give the same
// bytes on 1 and 2 threads (a moving ball, a moving camera).
TEST(OcclusionFilm, OtherAovsUnchangedAndBitIdenticalAcrossThreadCounts) {
  const std::string shapes =
      "  - {name: wall, type: rectangle, corner: [-20, -20, -6], edge_u: [40, 0, 0], edge_v: "
      "[0, 40, -8], material: grey, class: 3}\n"
      "  - {name: ball, type: sphere, centre: [0.2, -0.1, -3], radius: 0.6, material: grey, "
      "class: ball, motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [1, 0, 0]}]}\n";
  const std::string camera =
      ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [0.4, 0.1, -0.3]}]";
  const std::string base = "[depth, normal, instance_id, motion, valid";
  const RenderResult without =
      test::renderSequenceFrame(scene(shapes, camera, base + "]", 16), 1, 2);
  const SceneDescription d = scene(shapes, camera, base + ", occlusion, boundary]", 16);
  const RenderResult one = test::renderSequenceFrame(d, 1, 1),
                     two = test::renderSequenceFrame(d, 1, 2);
  ASSERT_EQ(one.aovs.channels, two.aovs.channels);
  EXPECT_EQ(one.aovs.pixels, two.aovs.pixels);
  EXPECT_EQ(without.image.pixels, two.image.pixels);
  int compared = 0;
  for (std::size_t c = 0; c < without.aovs.channels.size(); ++c) {
    const int k = two.aovs.channelIndex(without.aovs.channels[c]);
    ASSERT_GE(k, 0) << without.aovs.channels[c];
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x)
        ASSERT_EQ(without.aovs.at(x, y, static_cast<int>(c)), two.aovs.at(x, y, k))
            << without.aovs.channels[c] << " at " << x << "," << y;
    ++compared;
  }
  EXPECT_GT(compared, 20);
  EXPECT_GT(sum(one.aovs, "occlusion_fw.A"), 10.0);
  EXPECT_GT(sum(one.aovs, "boundary.A"), 50.0);
  for (float v : one.aovs.pixels) ASSERT_TRUE(std::isfinite(v));
  // occlusion alone (no motion channels) gives the same fractions.
  const Image alone =
      test::renderSequenceFrame(scene(shapes, camera, "[occlusion]", 16), 1, 2).aovs;
  for (const char* c : {"occlusion_fw.A", "occlusion_bw.A", "outside_fw.A", "outside_bw.A"})
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x) ASSERT_EQ(value(alone, x, y, c), value(one.aovs, x, y, c));
}

TEST(OcclusionFilm, NeedsAFramesBlock) {
  const auto text = [](const std::string& aovs) {
    return "camera: {position: [0, 0, 0], look_at: [0, 0, -1]}\n"
           "render: {aovs: " +
           aovs +
           "}\n"
           "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
           "shapes: [{type: sphere, centre: [0, 0, -3], radius: 1, material: grey}]\n";
  };
  try {
    loadSceneFromText(text("[depth, occlusion]"), "occlusion.yaml", ".");
    ADD_FAILURE() << "occlusion without frames was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("aov 'occlusion' needs a frames block"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(loadSceneFromText(text("[boundary]"), "boundary.yaml", "."));
}

// What the ray through (u, v) hits first in the boundary scene: 0 nothing, 1 the ball, 2
// the mesh's near square, 3 its far square (one shape), 4 the wall; and the distance (m).
struct Seen {
  int what = 0;
  double distance = 0.0;
};

// Boundary: a ball before a wall that covers the image's right part only (its edge against
// the empty background), and one mesh of two squares at 3 m and 4 m, the near one partly
// over the far one (a depth step within one shape). A pixel whose 32 × 32 footprint points
// all see one thing within 4.5 % of depth must be 0; one where each of two things takes at
// least 10 % of the footprint must be 1.
TEST(OcclusionBoundary, ObjectEdgesAndDepthStepsAgainstTheFootprint) {
  // Image rectangles [u0, u1] × [v0, v1] at depth zd as world corners.
  const auto corner = [](double u, double v, double zd) {
    return "[" + num((u - kC) / kF * zd) + ", " + num(-(v - kC) / kF * zd) + ", " + num(-zd) + "]";
  };
  const double wallU = 50.4, ball[3] = {0.35, -0.3, -3.0}, ballR = 0.2;
  const double nearSq[4] = {10.3, 30.3, 10.3, 30.3}, farSq[4] = {20.7, 40.7, 15.2, 25.6};
  const auto square = [&](const double* q, double zd) {
    return corner(q[0], q[2], zd) + ", " + corner(q[1], q[2], zd) + ", " + corner(q[1], q[3], zd) +
           ", " + corner(q[0], q[3], zd);
  };
  const std::string shapes = "  - {name: wall, type: rectangle, corner: " + corner(wallU, -50, 5) +
                             ", edge_u: [20, 0, 0], " +
                             "edge_v: [0, -20, 0], material: grey}\n"
                             "  - {name: ball, type: sphere, centre: [" +
                             num(ball[0]) + ", " + num(ball[1]) + ", " + num(ball[2]) +
                             "], radius: " + num(ballR) +
                             ", material: grey}\n"
                             "  - {name: steps, type: mesh, material: grey, vertices: [" +
                             square(nearSq, 3) + ", " + square(farSq, 4) +
                             "], faces: [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]}\n";
  const Image a = test::renderSequenceFrame(scene(shapes, "", "[boundary]"), 1).aovs;
  const auto seen = [&](double u, double v) {
    const glm::dvec3 dir = rayThrough(u, v);
    const double len = glm::length(dir);
    Seen s;
    const auto closer = [&](int what, double t) {
      if (t > 0.0 && (s.what == 0 || t * len < s.distance)) s = {what, t * len};
    };
    closer(1, sphereHit(dir, glm::dvec3(ball[0], ball[1], ball[2]), ballR));
    const auto in = [&](const double* q) {
      return u >= q[0] && u <= q[1] && v >= q[2] && v <= q[3];
    };
    if (in(nearSq)) closer(2, 3.0);
    if (in(farSq)) closer(3, 4.0);
    if (u >= wallU) closer(4, 5.0);
    return s;
  };
  int zeros = 0, ones = 0;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      int count[5] = {};
      double nearest = 1e9, farthest = 0.0;
      constexpr int kN = 32;
      for (int j = 0; j < kN; ++j)
        for (int i = 0; i < kN; ++i) {
          const Seen s = seen(x - 0.5 + (i + 0.5) / kN, y - 0.5 + (j + 0.5) / kN);
          ++count[s.what];
          if (s.what == 0) continue;
          nearest = std::min(nearest, s.distance);
          farthest = std::max(farthest, s.distance);
        }
      const double b = value(a, x, y, "boundary.A");
      const int kinds =
          static_cast<int>(std::count_if(count, count + 5, [](int c) { return c > 0; }));
      if (kinds == 1 && (count[0] > 0 || farthest - nearest < 0.045 * nearest)) {
        ASSERT_EQ(b, 0.0) << x << "," << y;
        ++zeros;
      }
      if (std::count_if(count, count + 5, [](int c) { return c >= kN * kN / 10; }) >= 2) {
        ASSERT_EQ(b, 1.0) << x << "," << y;
        ++ones;
      }
    }
  std::printf("boundary: %d pixels 0 and %d pixels 1 as the footprint says\n", zeros, ones);
  EXPECT_GT(zeros, kRes * kRes * 8 / 10);
  EXPECT_GT(ones, 150);
}

}  // namespace occlusion_film_test
}  // namespace camsim
