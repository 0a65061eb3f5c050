// Paraxial data of LensSystem against closed forms: the thick lens, Gullstrand's doublet,
// Newton's imaging equation, the pupils found with real rays; the three published lenses'
// focal lengths; the longitudinal chromatic aberration of a BK7 singlet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "integrator/camera/lens_system.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/lens_test_support.h"

namespace camsim {
namespace lens_system_test {

TEST(LensSystem, SingletMatchesTheThickLensFormulas) {
  // R1 = 50 mm, R2 = −80 mm, t = 6 mm, n = 1.6, the stop 5 mm behind.
  const LensSystem lens = test::lensFromText("50 6 1.6 30\n-80 5 1 30\n0 0 0 20\n");
  const ParaxialData p = lens.paraxial();
  const double n = 1.6, r1 = 0.050, r2 = -0.080, t = 0.006;
  const double f = 1.0 / ((n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * t / (n * r1 * r2)));
  // The issue asks 0.1 %; the formulas are exact in paraxial optics, so 1e-12 holds.
  EXPECT_NEAR(p.effectiveFocalLength / f, 1.0, 1e-12);
  // Behind the lens's rear vertex (z = 5 mm here) BFL = f (1 − (n − 1) t / (n R1)).
  EXPECT_NEAR(p.backFocalLength + 0.005, f * (1.0 - (n - 1.0) * t / (n * r1)), 1e-14);
  EXPECT_NEAR(p.frontFocalLength, f * (1.0 + (n - 1.0) * t / (n * r2)), 1e-14);
  // Principal planes (inside the lens): H at −f (n − 1) t / (n R2) behind the front
  // vertex, H' at f (n − 1) t / (n R1) in front of the lens's rear vertex.
  EXPECT_NEAR(p.frontPrincipalPlaneZ, p.totalTrack + f * (n - 1.0) * t / (n * r2), 1e-14);
  EXPECT_NEAR(p.rearPrincipalPlaneZ, 0.005 + f * (n - 1.0) * t / (n * r1), 1e-14);
}

TEST(LensSystem, CementedDoubletMatchesGullstrand) {
  // An achromat: R = 61.47, −44.64, −129.94 mm; 6 mm of n 1.5168, 2.5 mm of n 1.6727.
  const LensSystem lens = test::lensFromText(
      "0 1 0 25\n61.47 6 1.5168 30\n-44.64 2.5 1.6727 30\n"
      "-129.94 0 1 30\n");
  const double n1 = 1.5168, n2 = 1.6727, t1 = 0.006, t2 = 0.0025;
  const double p1 = (n1 - 1.0) / 0.06147, p2 = (n2 - n1) / -0.04464, p3 = (1.0 - n2) / -0.12994;
  // Surfaces 1 and 2 in glass n1: Gullstrand's power and the rear principal plane's shift
  // from surface 2 (δ' = −n2 (t1/n1) φ1/φ12); then that system and surface 3, (t2 − δ') in n2.
  const double p12 = p1 + p2 - t1 / n1 * p1 * p2;
  const double shift = -n2 * (t1 / n1) * p1 / p12;
  const double power = p12 + p3 - (t2 - shift) / n2 * p12 * p3;
  EXPECT_NEAR(lens.paraxial().effectiveFocalLength * power, 1.0, 1e-12);
}

TEST(LensSystem, PublishedLensesHaveTheirFocalLengths) {
  // Paraxial and traced with a near-axis parallel ray (h = 1 µm); both within 1 % of
  // the published focal length (the double-Gauss, scaled from 100 mm, is 50.36 mm).
  struct Case {
    const char* file;
    double published;
  };
  for (const Case& c : {Case{"dgauss.50mm.dat", 0.050}, Case{"fisheye.10mm.dat", 0.010},
                        Case{"telephoto.250mm.dat", 0.250}}) {
    const LensSystem lens = test::cameraLens(c.file);
    const ParaxialData p = lens.paraxial();
    const std::optional<double> traced = lens.tracedFocalLength(1e-6);
    ASSERT_TRUE(traced) << c.file;
    std::printf("%s: EFL paraxial %.4f mm, traced %.4f mm (%+.2f %%), BFL %.4f mm, f/%.3f\n",
                c.file, p.effectiveFocalLength * 1e3, *traced * 1e3,
                100.0 * (*traced / c.published - 1.0), p.backFocalLength * 1e3, p.fNumber);
    EXPECT_NEAR(p.effectiveFocalLength / c.published, 1.0, 0.01) << c.file;
    EXPECT_NEAR(*traced / c.published, 1.0, 0.01) << c.file;
    EXPECT_NEAR(*traced / p.effectiveFocalLength, 1.0, 1e-6) << c.file;
  }
}

TEST(LensSystem, Bk7SingletLongitudinalColourMatchesTheThinLens) {
  // A plano-convex BK7 lens, f = 100 mm at d, 2.5 mm thick; the stop in front.
  const LensSystem lens = test::lensFromText("0 1 0 20\n51.68 2.5 1.5168 20 glass=BK7\n0 0 1 20\n");
  const Glass& bk7 = lens.prescription().surfaces[1].medium;
  const double f = lens.paraxial().effectiveFocalLength;
  const double expected =
      f * (bk7.index(kLambdaFNm) - bk7.index(kLambdaCNm)) / (bk7.index(kLambdaDNm) - 1.0);
  const double shift = lens.focusSensorDistance(kInfiniteDistance, kLambdaCNm) -
                       lens.focusSensorDistance(kInfiniteDistance, kLambdaFNm);
  std::printf("BK7 singlet: f %.3f mm, focus shift C − F %.4f mm, f (nF − nC)/(nd − 1) %.4f mm\n",
              f * 1e3, shift * 1e3, expected * 1e3);
  EXPECT_NEAR(shift / expected, 1.0, 0.02);
  // The same with real rays, stopped down to f/50 (best-RMS focus of the real bundle).
  LensSystem slow = lens;
  slow.setStop(0.002);
  const double traced =
      slow.focusSensorDistance(kInfiniteDistance, kLambdaCNm, FocusMethod::kBestRms) -
      slow.focusSensorDistance(kInfiniteDistance, kLambdaFNm, FocusMethod::kBestRms);
  EXPECT_NEAR(traced / expected, 1.0, 0.02);
  EXPECT_NEAR(traced / shift, 1.0, 1e-3);
}

TEST(LensSystem, FocusObeysNewtonsEquationAndBreathes) {
  const LensSystem lens = test::cameraLens("dgauss.50mm.dat");
  const ParaxialData inf = lens.paraxial();
  EXPECT_DOUBLE_EQ(lens.focusSensorDistance(), inf.backFocalLength);
  for (const double d : {0.5, 1.0, 3.0}) {
    const ParaxialData p = lens.paraxial(kLambdaDNm, d);
    const double s = lens.focusSensorDistance(d);
    EXPECT_DOUBLE_EQ(s, p.imageDistance);
    const double f = p.effectiveFocalLength;
    EXPECT_NEAR((d - p.frontFocalLength) * (s - p.backFocalLength) / (f * f), 1.0, 1e-12);
    // m = −f / x (x the object's distance from the front focal point).
    EXPECT_NEAR(p.magnification, -f / (d - p.frontFocalLength), 1e-12);
    // Working f-number N_w = (1 + |m| / p) N with the pupil magnification p.
    EXPECT_NEAR(p.workingFNumber,
                (1.0 + std::abs(p.magnification) / p.pupilMagnification) * p.fNumber, 1e-9);
    // Focus breathing: a closer focus narrows the field of view.
    EXPECT_LT(p.fieldOfViewDiagonal, inf.fieldOfViewDiagonal);
  }
  EXPECT_NEAR(inf.fieldOfViewHorizontal, 2.0 * std::atan(0.018 / inf.effectiveFocalLength), 1e-15);
  // Best-RMS focus is a minimum of the real bundle's spot size: checked through the
  // paraxial image it departs from by less than the depth of focus at f/2 (±0.05 mm).
  const double best =
      lens.focusSensorDistance(kInfiniteDistance, kLambdaDNm, FocusMethod::kBestRms);
  EXPECT_LT(std::abs(best - inf.backFocalLength), 5e-5);
}

TEST(LensSystem, StopForFNumberAndPupils) {
  LensSystem lens = test::cameraLens("dgauss.50mm.dat");
  EXPECT_NEAR(lens.minFNumber(), lens.paraxial().fNumber, 1e-12);
  lens.setStop(lens.stopDiameterForFNumber(4.0));
  EXPECT_NEAR(lens.paraxial().fNumber, 4.0, 1e-12);
  // A front stop is its own entrance pupil.
  const LensSystem front = test::lensFromText("0 10 0 8\n60 4 1.5 30\n-60 0 1 30\n");
  const ParaxialData p = front.paraxial();
  EXPECT_NEAR(p.entrancePupilZ, front.frontVertexZ(), 1e-15);
  EXPECT_NEAR(p.entrancePupilDiameter, 0.008, 1e-15);
}

TEST(LensSystem, ForCameraRejectsWhatCannotImage) {
  for (const std::string text : {"0 1 0 10\n-50 4 1.5 20\n50 0 1 20\n",  // diverging
                                 "0 1 0 10\n0 4 1.5 20\n0 0 1 20\n"}) {  // a plate
    try {
      LensSystem::forCamera(parseLensPrescription(text, "weak.dat"));
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "weak.dat");
    }
  }
}

TEST(LensSystem, ParaxialFieldsAreNamedOnceAndFinite) {
  const LensSystem lens = test::cameraLens("telephoto.250mm.dat");
  std::set<std::string> names;
  for (const ParaxialField& field : paraxialFields(lens.paraxial(kLambdaDNm, 5.0))) {
    EXPECT_TRUE(names.insert(field.name).second) << field.name;
    EXPECT_TRUE(std::isfinite(field.value)) << field.name;
  }
  EXPECT_EQ(names.size(), 22u);
  for (const ParaxialField& field : paraxialFields(lens.paraxial()))  // at infinity
    EXPECT_EQ(std::isfinite(field.value), field.name != std::string("object_distance"));
}

}  // namespace lens_system_test
}  // namespace camsim
