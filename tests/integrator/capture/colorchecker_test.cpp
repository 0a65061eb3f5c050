// The whole chain on the ColorChecker scene, through the capture library call (capture.h):
// render (spectral) → sensor electrons → auto-exposure → expose (noise off) → ISP (white
// balance, demosaic, CCM fitted from the sensor's QE) → ACEScg, measured per patch and compared in CIELAB (D65 white) with the closed-form
// colour of each patch: reflectance × illuminant × CMFs (Bradford-adapted to D65).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include <glm/matrix.hpp>

#include "integrator/capture/capture.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/isp/color_correction.h"
#include "sensor/isp/color_difference.h"
#include "sensor/model/exposure_control.h"
#include "sensor/model/sensor_model.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

const std::filesystem::path kSource(CAMSIM_SOURCE_DIR);
const std::filesystem::path kChartCsv =
    kSource / "luts/spectra/colorchecker_classic_reflectance.csv";

struct ChartResult {
  std::vector<glm::dvec3> labMeasured, labReference;
  double meanDeltaE = 0.0, maxDeltaE = 0.0;
};

// Renders the chart under `illuminant` through `sensorName`, develops it, measures it.
ChartResult measureChart(const std::string& sensorName, const std::string& illuminant,
                         bool balanceOnGreyCard = false) {
  SceneDescription d = loadScene(kSource / "scenes/colorchecker.yaml");
  d.camera.resolution = {300, 200};
  SensorSettings sensor;
  sensor.spec = loadSensorSpec(sensorName, kSource / "luts");
  sensor.iso = sensor.spec.baseIso;
  sensor.noise = NoiseMode::kNone;
  d.camera.sensorSize = glm::dvec2(d.camera.resolution) * sensor.spec.pixelPitchM;
  d.camera.focalLength =
      d.camera.sensorSize.x / 0.3;  // the 0.3 m wide chart fills the frame at 1 m
  const Spectrum light = cieIlluminant(illuminant);
  d.shapes[0].emission->radiance = light * (1000.0 / luminance(light));  // the dome, 1000 cd/m²
  // Exposed on the brightest photosites — the white patch (19, bottom left) — at 70 % of
  // saturation, as one exposes a chart.
  sensor.autoExposure = AutoExposure{AutoExposure::Metering::kPercentile, 0.7, 100.0};
  d.sensor = sensor;
  d.render.spp =
      64;  // render noise under spiky F2 needs it: neutral patches move by ~0.5 at 16 spp
  d.isp.illuminant = illuminant;
  if (balanceOnGreyCard) {  // patch 20, "neutral 8": row 3, column 1
    d.isp.whiteBalance = IspSettings::WhiteBalance::kRegion;
    d.isp.region = {65, 165, 20, 20};
  }
  const CaptureResult captured = capture(d);
  const DevelopedImage& dev = *captured.developed;
  const glm::dmat3 workingToXyz = glm::inverse(xyzD65ToWorkingSpace(RgbColorSpace::acesCg()));

  // Reference: each patch's XYZ under the illuminant (white Y = 1), adapted to D65.
  const SpectralTable chart = readSpectralCsv(kChartCsv);
  const glm::dvec3 illuminantWhite = reflectanceToXyz(Spectrum::constant(1.0), light);
  const glm::dmat3 cat = bradfordAdaptation(illuminantWhite, d65WhiteXyz());
  std::vector<glm::dvec3> measured, reference;
  for (int p = 0; p < 24; ++p) {
    const int row = p / 6, col = p % 6;
    const int cx = 150 + (col * 50 - 125), cy = 100 + (row * 50 - 75);
    glm::dvec3 sum(0.0);
    for (int y = cy - 10; y < cy + 10; ++y)
      for (int x = cx - 10; x < cx + 10; ++x)
        sum +=
            glm::dvec3(dev.working.at(x, y, 0), dev.working.at(x, y, 1), dev.working.at(x, y, 2));
    // Flat-field: undo the lens's cos⁴θ fall-off at the patch centre (up to 4 % here).
    const double sx = ((cx + 0.5) / 300.0 - 0.5) * d.camera.sensorSize.x,
                 sy = ((cy + 0.5) / 200.0 - 0.5) * d.camera.sensorSize.y;
    const double cos2 =
        1.0 / (1.0 + (sx * sx + sy * sy) / (d.camera.focalLength * d.camera.focalLength));
    measured.push_back(workingToXyz * (sum / 400.0) / (cos2 * cos2));
    reference.push_back(
        cat *
        reflectanceToXyz(chart.spectrum(static_cast<size_t>(p), Extrapolation::kClamp), light));
  }
  // Normalise the exposure on the white patch (19), as one does with a real chart.
  const double scale = reference[18].y / measured[18].y;
  ChartResult result;
  for (int p = 0; p < 24; ++p) {
    result.labMeasured.push_back(xyzToLab(measured[static_cast<size_t>(p)] * scale, d65WhiteXyz()));
    result.labReference.push_back(xyzToLab(reference[static_cast<size_t>(p)], d65WhiteXyz()));
    const double de = deltaE2000(result.labMeasured.back(), result.labReference.back());
    result.meanDeltaE += de / 24.0;
    result.maxDeltaE = std::max(result.maxDeltaE, de);
  }
  std::printf("ColorChecker %-18s under %-4s: mean dE2000 %.3f, max %.3f\n", sensorName.c_str(),
              illuminant.c_str(), result.meanDeltaE, result.maxDeltaE);
  return result;
}

// Through the ideal XYZ sensor the rendered chart is colorimetrically exact up to render
// noise and the 16-bit quantisation: mean ΔE2000 < 1 (the bound).
TEST(ColorChecker, IdealXyzSensorMatchesSpectralColorimetry) {
  const ChartResult r = measureChart("ideal-xyz", "D65");
  EXPECT_LT(r.meanDeltaE, 1.0);
}

// Through a measured camera (Nikon D850 curves) with its fitted CCM: mean ΔE2000 < 3
// under D65 and under illuminant A (the bound; max reported).
TEST(ColorChecker, MeasuredCameraWithFittedCcm) {
  for (const char* illuminant : {"D65", "A"}) {
    const ChartResult r = measureChart("fullframe-d850", illuminant);
    EXPECT_LT(r.meanDeltaE, 3.0) << illuminant;
  }
}

// White balance makes the neutral patches neutral under A and F2 (|a*|, |b*| < 1):
// balanced on a grey card (patch 20, "neutral 8"), as a photographer does, the neutral
// patches 20–24 come out neutral. Patch 19 ("white 9.5") is excluded: its reflectance is
// not spectrally flat (its own b* is +2.3 under A), so it is not a neutral. A spectrally
// flat grey is neutral to 1e-12 with illuminant white balance (white_balance_test.cpp).
TEST(ColorChecker, WhiteBalanceMakesNeutralPatchesNeutral) {
  for (const char* illuminant : {"A", "F2"}) {
    const ChartResult r = measureChart("fullframe-d850", illuminant, true);
    for (int p = 19; p < 24; ++p) {
      const glm::dvec3& lab = r.labMeasured[static_cast<size_t>(p)];
      std::printf("  %s patch %d: a* %.2f b* %.2f\n", illuminant, p + 1, lab.y, lab.z);
      EXPECT_LT(std::abs(lab.y), 1.0) << illuminant << " patch " << p + 1 << " a*";
      EXPECT_LT(std::abs(lab.z), 1.0) << illuminant << " patch " << p + 1 << " b*";
    }
  }
}

}  // namespace
}  // namespace camsim
