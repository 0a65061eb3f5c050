// Exit-pupil bounds: every ray that gets through falls inside its film point's bound
// (nothing is missed), the sampler's density is right (two samplers and a brute-force
// count agree on the passing area), and few sampled rays are lost (the fraction printed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "integrator/camera/lens_pupil.h"
#include "integrator/sampling/rng.h"
#include "tests/integrator/lens_test_support.h"

namespace camsim {
namespace lens_pupil_test {

const glm::dvec2 kSensor(0.036, 0.024);  // m
const double kFilmRadius = 0.5 * std::hypot(0.036, 0.024);

struct Uniform {
  Pcg32 rng;
  double operator()() { return (rng.next() + 0.5) * 0x1p-32; }
};

bool passes(const LensSystem& lens, double s, glm::dvec2 film, glm::dvec2 rear) {
  const glm::dvec3 o(film, -s);
  return lens.traceFromFilm({o, glm::normalize(glm::dvec3(rear, 0.0) - o)}, kLambdaDNm).has_value();
}

TEST(LensPupil, EveryPassingRayIsInsideItsBound) {
  for (const char* file : {"dgauss.50mm.dat", "fisheye.10mm.dat", "telephoto.250mm.dat"}) {
    const LensSystem lens = test::cameraLens(file);
    const double s = lens.focusSensorDistance();
    const ExitPupilBounds bounds(lens, s, kFilmRadius);
    // Film points uniform over the film disc, rear points over a square twice the rear
    // element: 300 000 pairs, of which tens of thousands pass.
    Uniform u{Pcg32(5, 1)};
    const double e = 2.0 * lens.rearClearRadius();
    int passing = 0, outside = 0;
    for (int i = 0; i < 300000; ++i) {
      const double r = kFilmRadius * std::sqrt(u()), phi = 2.0 * M_PI * u();
      const glm::dvec2 film(r * std::cos(phi), r * std::sin(phi));
      const glm::dvec2 rear((2.0 * u() - 1.0) * e, (2.0 * u() - 1.0) * e);
      if (!passes(lens, s, film, rear)) continue;
      ++passing;
      outside += bounds.covers(film, rear) ? 0 : 1;
    }
    std::printf("%s: %d of 300000 random pairs pass, %d outside their bound\n", file, passing,
                outside);
    EXPECT_GT(passing, 5000) << file;
    EXPECT_EQ(outside, 0) << file << ": " << outside << " of " << passing;
  }
}

TEST(LensPupil, SampledDensityGivesThePassingArea) {
  // The rear-plane area whose rays pass, for three film points of the double-Gauss,
  // estimated three ways: bound area × passing fraction of sample(); the same with points
  // uniform in the bound's box; points uniform in a square around the rear element.
  const LensSystem lens = test::cameraLens("dgauss.50mm.dat");
  const double s = lens.focusSensorDistance();
  const ExitPupilBounds bounds(lens, s, kFilmRadius);
  constexpr int n = 200000;
  for (const double r : {0.0, 0.012, 0.020}) {
    const glm::dvec2 film(0.6 * r, -0.8 * r);
    Uniform u{Pcg32(9, static_cast<std::uint64_t>(r * 1e4))};
    int viaSample = 0, viaBox = 0, viaSquare = 0;
    double area = 0.0;
    const int k = std::min(static_cast<int>(r / kFilmRadius * bounds.intervals()), 63);
    const PupilBox& box = bounds.bound(k);
    const double e = 1.5 * lens.rearClearRadius();
    for (int i = 0; i < n; ++i) {
      const std::optional<PupilSample> p = bounds.sample(film, {u(), u()});
      ASSERT_TRUE(p);
      area = p->area;
      viaSample += passes(lens, s, film, glm::dvec2(p->point)) ? 1 : 0;
      // The box in the film point's frame, turned to the film point's angle.
      const glm::dvec2 q = box.lo + glm::dvec2(u(), u()) * (box.hi - box.lo);
      const glm::dvec2 c = r > 0.0 ? film / r : glm::dvec2(1.0, 0.0);
      viaBox += passes(lens, s, film, {c.x * q.x - c.y * q.y, c.y * q.x + c.x * q.y}) ? 1 : 0;
      viaSquare += passes(lens, s, film, {(2.0 * u() - 1.0) * e, (2.0 * u() - 1.0) * e}) ? 1 : 0;
    }
    const double a1 = area * viaSample / n, a2 = box.area() * viaBox / n;
    const double a3 = 4.0 * e * e * viaSquare / n;
    std::printf(
        "dgauss film r %.0f mm: passing area %.3f / %.3f / %.3f mm² (bound, box, "
        "square); lost %.1f %% from the bound, %.1f %% from the box\n",
        r * 1e3, a1 * 1e6, a2 * 1e6, a3 * 1e6, 100.0 * (1.0 - viaSample / double(n)),
        100.0 * (1.0 - viaBox / double(n)));
    // Binomial standard errors: < 0.5 % for the bound and box, ≈ 1 % for the square;
    // tolerance 4 %.
    EXPECT_NEAR(a1 / a3, 1.0, 0.04) << r;
    EXPECT_NEAR(a1 / a2, 1.0, 0.02) << r;
  }
}

TEST(LensPupil, FewSampledRaysAreLost) {
  // Film points uniform over a 36 × 24 mm sensor, focus at infinity, full aperture.
  struct Case {
    const char* file;
    double maxLost;  // measured + margin (docs/camera.md)
  };
  for (const Case& c : {Case{"dgauss.50mm.dat", 0.12}, Case{"fisheye.10mm.dat", 0.16},
                        Case{"telephoto.250mm.dat", 0.11}}) {
    const LensSystem lens = test::cameraLens(c.file);
    const ExitPupilBounds bounds(lens, lens.focusSensorDistance(), kFilmRadius);
    const PupilLoss loss = measurePupilLoss(lens, bounds, kSensor, 100000);
    std::printf(
        "%s: %.1f %% of sampled rays lost (%lld of %lld); %lld film points outside "
        "the image circle; %lld rays traced for the bounds\n",
        c.file, 100.0 * loss.lostFraction(), loss.lost, loss.rays, loss.noBox, bounds.raysTraced());
    EXPECT_LT(loss.lostFraction(), c.maxLost) << c.file;
  }
}

// Stopped down until the bundle on the rear plane is about one coarse cell wide (f/34: ≈ 1 mm
// of a 0.94 mm cell) or far narrower (f/128, the slowest a traced lens takes): found by
// probing, film radii whose bundle fell between the cell centres got no bound (black pixels;
// from f/40 on, every radius: the lens was refused), or one built from a single cell
// (exposure 0.8 of the camera equation's at f/30). Now every radius of the image circle has a bound, the passing area
// it gives agrees with a brute-force count around the bundle, and few sampled rays are lost.
TEST(LensPupil, NarrowBundlesOfAStoppedDownLensAreFound) {
  struct Case {
    const char* file;
    double fNumber;
    int imaged;  // intervals of the 64 inside the image circle (the fisheye's: 13 of 21.6 mm)
  };
  for (const auto& [file, fNumber, imaged] :
       {Case{"dgauss.50mm.dat", 34.0, 64}, Case{"dgauss.50mm.dat", kMaxTracedFNumber, 64},
        Case{"fisheye.10mm.dat", kMaxTracedFNumber, 38},
        Case{"telephoto.250mm.dat", kMaxTracedFNumber, 64}}) {
    LensSystem lens = test::cameraLens(file);
    lens.setStop(lens.stopDiameterForFNumber(fNumber));
    const double s = lens.focusSensorDistance();
    const ExitPupilBounds bounds(lens, s, kFilmRadius);
    for (int k = 0; k < imaged; ++k)
      EXPECT_GT(bounds.area(k), 0.0) << file << " f/" << fNumber << " interval " << k;
    const PupilLoss loss = measurePupilLoss(lens, bounds, kSensor, 20000);
    // On axis: the bound's estimate against points uniform in a square of 1.5 times the
    // bound's box (the bundle is centred on the axis there).
    const glm::dvec2 film(0.0, 0.0);
    const PupilBox& box = bounds.bound(0);
    const double e = 1.5 * std::max({-box.lo.x, box.hi.x, box.hi.y});
    Uniform u{Pcg32(3, static_cast<std::uint64_t>(fNumber))};
    constexpr int n = 200000;
    int viaSample = 0, viaSquare = 0;
    double area = 0.0;
    for (int i = 0; i < n; ++i) {
      const std::optional<PupilSample> p = bounds.sample(film, {u(), u()});
      ASSERT_TRUE(p);
      area = p->area;
      viaSample += passes(lens, s, film, glm::dvec2(p->point)) ? 1 : 0;
      viaSquare += passes(lens, s, film, {(2.0 * u() - 1.0) * e, (2.0 * u() - 1.0) * e}) ? 1 : 0;
    }
    const double a1 = area * viaSample / n, a3 = 4.0 * e * e * viaSquare / n;
    std::printf(
        "%s f/%.0f: on-axis passing area %.4g / %.4g mm² (bound, square); %.1f %% "
        "of sampled rays lost over the sensor\n",
        file, fNumber, a1 * 1e6, a3 * 1e6, 100.0 * loss.lostFraction());
    EXPECT_NEAR(a1 / a3, 1.0, 0.04) << file << " f/" << fNumber;  // binomial errors < 1 %
    EXPECT_LT(loss.lostFraction(), 0.5) << file << " f/" << fNumber;
  }
}

}  // namespace lens_pupil_test
}  // namespace camsim
