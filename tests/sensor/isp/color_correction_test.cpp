// Tests for sensor/color_correction: the ColorChecker least-squares CCM reproduces the
// chart's XYZ (ΔE2000 printed per sensor and illuminant), an ideal colorimetric sensor
// gets the identity, the white constraint holds, the Bradford and working-space matrices
// map whites to whites, and the fitted CCM works on an image through the whole ISP.
#include "sensor/isp/color_correction.h"

#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>
#include <glm/matrix.hpp>

#include "sensor/base/input_error.h"
#include "sensor/isp/color_difference.h"
#include "sensor/isp/demosaic.h"
#include "sensor/isp/isp_black_level.h"
#include "sensor/isp/white_balance.h"
#include "sensor/model/sensor_model.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"
#include "tests/support/lut_paths.h"

namespace camsim {
namespace {

void expectNear(const glm::dmat3& m, const glm::dmat3& expected, double tolerance,
                const char* what) {
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row)
      EXPECT_NEAR(m[col][row], expected[col][row], tolerance)
          << what << " row " << row << " col " << col;
}

void expectNear(const glm::dvec3& v, const glm::dvec3& expected, double tolerance,
                const char* what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(v[i], expected[i], tolerance) << what << " " << i;
}

// Mean ΔE2000 < 3 on the chart for the two measured-QE presets under D65 and A.
TEST(ColorCorrection, ColorCheckerDeltaE2000BelowThreeForMeasuredSensors) {
  for (const char* preset : {"fullframe-d850", "smartphone-1.4um"}) {
    const SensorSpec s = loadSensorSpec(preset, test::kLuts);
    for (const char* ill : {"D65", "A"}) {
      for (const bool preserveWhite : {true, false}) {
        ColorCorrectionOptions options;
        options.preserveWhite = preserveWhite;
        const Spectrum illuminant = cieIlluminant(ill);
        const ColorCorrection cc =
            fitColorCorrection(s.qe, illuminant, test::kColorChecker, options);
        const ChartError e = colorCheckerError(cc, s.qe, illuminant, test::kColorChecker);
        ASSERT_EQ(e.deltaE.size(), 24u);
        std::printf("[ %-16s %-3s %-14s ] mean ΔE00 %.2f  max %.2f (patch %zu)\n", preset, ill,
                    preserveWhite ? "white-preserve" : "unconstrained", e.mean, e.max,
                    static_cast<size_t>(std::max_element(e.deltaE.begin(), e.deltaE.end()) -
                                        e.deltaE.begin()) +
                        1);
        EXPECT_LT(e.mean, 3.0) << preset << " " << ill;
      }
    }
  }
}

TEST(ColorCorrection, IdealXyzSensorGetsTheIdentity) {
  // QE·λ ∝ x̄ȳz̄: balanced camera = XYZ / XYZ_white, so M = diag(XYZ_white) and
  // M · diag(g) = I. Tolerance 1e-3 (the QE is stored in float: ~1e-6 in practice).
  const SensorSpec ideal = loadSensorSpec("ideal-xyz", test::kLuts);
  const Spectrum d65 = cieIlluminant("D65");
  for (const bool preserveWhite : {true, false}) {
    ColorCorrectionOptions options;
    options.preserveWhite = preserveWhite;
    const ColorCorrection cc = fitColorCorrection(ideal.qe, d65, test::kColorChecker, options);
    expectNear(cc.rawToXyz(), glm::dmat3(1.0), 1e-3, "raw → XYZ");
    const glm::dvec3 w = d65WhiteXyz();
    expectNear(cc.cameraToXyz,
               glm::dmat3(glm::dvec3(w.x, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, w.z)), 1e-3,
               "CCM");
    EXPECT_LT(colorCheckerError(cc, ideal.qe, d65, test::kColorChecker).max, 1e-3);
  }
  // Under A the fit adds the adaptation: raw → XYZ is Bradford(A → D65).
  const Spectrum a = cieIlluminant("A");
  const ColorCorrection ccA = fitColorCorrection(ideal.qe, a, test::kColorChecker);
  expectNear(ccA.rawToXyz(), ccA.adaptation, 1e-3, "raw → XYZ under A");
}

TEST(ColorCorrection, WhitePreservationMapsTheBalancedWhiteToD65) {
  const SensorSpec s = loadSensorSpec("fullframe-d850", test::kLuts);
  for (const char* ill : {"D65", "A", "F2"}) {
    const ColorCorrection cc = fitColorCorrection(s.qe, cieIlluminant(ill), test::kColorChecker);
    expectNear(cc.cameraToXyz * glm::dvec3(1.0), d65WhiteXyz(), 1e-12, ill);
    // ACEScg of the white is (1, 1, 1).
    expectNear(cc.cameraToWorking() * glm::dvec3(1.0), glm::dvec3(1.0), 1e-9, ill);
    EXPECT_EQ(cc.workingSpace, "acescg");
  }
  ColorCorrectionOptions free;
  free.preserveWhite = false;
  const ColorCorrection cc =
      fitColorCorrection(s.qe, cieIlluminant("A"), test::kColorChecker, free);
  const glm::dvec3 w = cc.cameraToXyz * glm::dvec3(1.0);
  EXPECT_GT(glm::length(w - d65WhiteXyz()), 1e-6);  // not exact without the constraint
  EXPECT_LT(glm::length(w - d65WhiteXyz()), 0.05);  // but close
}

TEST(ColorCorrection, BradfordAndWorkingSpaceMatrices) {
  const glm::dvec3 d65 = d65WhiteXyz();
  const glm::dvec3 a = reflectanceToXyz(Spectrum::constant(1.0), cieIlluminant("A"));
  expectNear(bradfordAdaptation(a, d65) * a, d65, 1e-12, "A → D65");
  expectNear(bradfordAdaptation(d65, d65), glm::dmat3(1.0), 1e-12, "D65 → D65");
  // D65 xy from the tabulated spectrum: (0.3127, 0.3290) to 4 decimals.
  const Chromaticity xy = xyzToChromaticity(d65);
  EXPECT_NEAR(xy.x, 0.3127, 1e-4);
  EXPECT_NEAR(xy.y, 0.3290, 1e-4);
  // Working spaces: the D65 white becomes RGB (1, 1, 1).
  const glm::dmat3 toAcesCg = xyzD65ToWorkingSpace(RgbColorSpace::acesCg());
  expectNear(toAcesCg * d65, glm::dvec3(1.0), 1e-9, "ACEScg");
  const glm::dmat3 to709 = xyzD65ToWorkingSpace(RgbColorSpace::linearRec709());
  expectNear(to709 * d65, glm::dvec3(1.0), 1e-9, "Rec.709");
  // Rec.709's white is D65 already: W is its rgbFromXyz up to the 1e-4 xy difference.
  expectNear(to709, RgbColorSpace::linearRec709().rgbFromXyz(), 2e-3, "Rec.709 W");
}

TEST(ColorCorrection, ApplyColorMatrixAndErrors) {
  Image rgb(2, 1, {"R", "G", "B"});
  rgb.pixels = {1.0f, 0.0f, 0.0f, 0.2f, 0.4f, 0.6f};
  glm::dmat3 m(0.0);
  m[0] = {1.0, 2.0, 3.0};  // column 0
  m[1] = {0.0, 1.0, 0.0};
  m[2] = {0.0, 0.0, 2.0};
  const Image out = applyColorMatrix(rgb, m, {"X", "Y", "Z"});
  EXPECT_EQ(out.channels, (std::vector<std::string>{"X", "Y", "Z"}));
  EXPECT_FLOAT_EQ(out.at(0, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 1), 2.0f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 2), 3.0f);
  EXPECT_FLOAT_EQ(out.at(1, 0, 1), 0.8f);  // 2·0.2 + 0.4
  EXPECT_FLOAT_EQ(out.at(1, 0, 2), 1.8f);  // 3·0.2 + 2·0.6
  EXPECT_THROW(applyColorMatrix(Image(1, 1, {"Y"}), m, {"X", "Y", "Z"}), InputError);
  const SensorSpec s = loadSensorSpec("fullframe-d850", test::kLuts);
  EXPECT_THROW(fitColorCorrection({s.qe[0], s.qe[1]}, cieIlluminant("D65"), test::kColorChecker),
               InputError);
  EXPECT_THROW(fitColorCorrection(s.qe, cieIlluminant("D65"), "/nonexistent.csv"), InputError);
}

// The chart as an image through the whole ISP: 24 patches of 12 × 12 photosites, noise-free
// exposure under A (white at 80 % of saturation, 14-bit quantisation) → normalise →
// illuminant white balance → Malvar–He–Cutler → CCM → XYZ; the centre 4 × 4 of each patch
// against the chart's D65-adapted XYZ. Tolerance: mean ΔE00 < 3 (the fit's own residual
// plus quantisation; the patch centres are flat, so demosaicking adds nothing).
TEST(ColorCorrection, ChartImageThroughTheIspMatchesTheFit) {
  const SensorSpec s = loadSensorSpec("fullframe-d850", test::kLuts);
  const Spectrum ill = cieIlluminant("A");
  const SpectralTable chart = readSpectralCsv(test::kColorChecker);
  const int patch = 12;
  Image electrons(6 * patch, 4 * patch, {"expected"});
  const double scale = 0.8 * s.saturationElectrons(s.baseIso) /
                       cameraResponse(s.qe, Spectrum::constant(1.0), ill)[1];
  std::vector<glm::dvec3> reference;
  const glm::dmat3 adapt =
      bradfordAdaptation(reflectanceToXyz(Spectrum::constant(1.0), ill), d65WhiteXyz());
  for (int p = 0; p < 24; ++p) {
    const Spectrum r = chart.spectrum(static_cast<size_t>(p), Extrapolation::kClamp);
    const std::vector<double> c = cameraResponse(s.qe, r, ill);
    reference.push_back(adapt * reflectanceToXyz(r, ill) * 0.8);  // the exposure level
    for (int y = 0; y < patch; ++y)
      for (int x = 0; x < patch; ++x) {
        const int px = (p % 6) * patch + x, py = (p / 6) * patch + y;
        electrons.at(px, py, 0) =
            static_cast<float>(scale * c[static_cast<size_t>(s.cfa.channelAt(px, py))]);
      }
  }
  const RawImage raw = expose(electrons, s, {1.0 / 60.0, s.baseIso}, NoiseMode::kNone, 1, 0);
  const Image rgb =
      demosaic(applyWhiteBalance(normalizeRaw(raw), s.cfa, whiteBalanceFromIlluminant(s, ill)),
               s.cfa, DemosaicMethod::kMalvarHeCutler);
  const ColorCorrection cc = fitColorCorrection(s.qe, ill, test::kColorChecker);
  const Image xyz = applyColorMatrix(rgb, cc.cameraToXyz, {"X", "Y", "Z"});
  double mean = 0.0, worst = 0.0;
  const glm::dvec3 white = d65WhiteXyz() * 0.8;
  for (int p = 0; p < 24; ++p) {
    glm::dvec3 sum(0.0);
    for (int y = 4; y < 8; ++y)
      for (int x = 4; x < 8; ++x)
        for (int c = 0; c < 3; ++c)
          sum[c] += static_cast<double>(xyz.at((p % 6) * patch + x, (p / 6) * patch + y, c)) / 16.0;
    const double de =
        deltaE2000(xyzToLab(sum, white), xyzToLab(reference[static_cast<size_t>(p)], white));
    mean += de / 24.0;
    worst = std::max(worst, de);
  }
  std::printf("[ ISP chart, D850, A ] mean ΔE00 %.2f  max %.2f\n", mean, worst);
  EXPECT_LT(mean, 3.0);
}

}  // namespace
}  // namespace camsim
