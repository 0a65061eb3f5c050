// A rendered scene through the smartphone-1.4um sensor at a low light level shows the
// noise the EMVA 1288 model predicts on a flat patch; auto-exposure and brackets behave.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/io/exr_io.h"
#include "sensor/model/exposure_control.h"
#include "sensor/model/sensor_model.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

// A camera inside a uniformly emitting sphere (D65, 10 cd/m²: a dim room), f/2, 1/30 s:
// a flat field of a few hundred photo-electrons per green photosite.
const char* kFlatField =
    "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [256, 256], focal_length_mm: "
    "4,\n"
    "         f_number: 2, shutter: {open: 0, close: 0.0333}}\n"
    "sensor: {model: smartphone-1.4um, iso: 100, noise: full, noise_seed: 9}\n"
    "render: {max_depth: 0}\n"
    "shapes:\n"
    "  - {type: sphere, centre: [0, 0, 0], radius: 100, emission: {luminance: 10, two_sided: "
    "true}}\n";

TEST(SensorRender, FlatPatchMeanAndVarianceMatchEmvaModel) {
  const SceneDescription desc = loadSceneFromText(kFlatField, "flat.yaml", ".");
  ASSERT_TRUE(desc.sensor.has_value());
  const SensorSpec& spec = desc.sensor->spec;
  const Scene scene(desc);
  const SpectralResponse sensor =
      SpectralResponse::electrons(spec.cfa.channels, spec.qe, &spec.cfa);
  RenderOptions options;
  options.spp = 64;
  const RenderResult r = render(scene, sensor, options);
  const ExposureSettings exposure{desc.camera.shutter.effectiveTime(), desc.sensor->iso};
  const RawImage raw = expose(r.image, spec, exposure, NoiseMode::kFull, 9, 0);

  // Green photosites of the central 224×224 patch.
  double sumE = 0.0, sumE2 = 0.0, sumDn = 0.0, sumDn2 = 0.0;
  int n = 0;
  for (int y = 16; y < 240; ++y)
    for (int x = 16; x < 240; ++x) {
      if (spec.cfa.channels[static_cast<size_t>(spec.cfa.channelAt(x, y))] != "G") continue;
      const double e = static_cast<double>(r.image.at(x, y, 0)), dn = raw.at(x, y);
      sumE += e;
      sumE2 += e * e;
      sumDn += dn;
      sumDn2 += dn * dn;
      ++n;
    }
  const double muE = sumE / n, varE = sumE2 / n - muE * muE;  // render noise of the expectation
  const double muDn = sumDn / n, varDn = sumDn2 / n - muDn * muDn;
  const double K = spec.systemGain(desc.sensor->iso);
  const double dark = spec.darkCurrentAtTemperature() * exposure.exposureTimeS;
  // EMVA 1288 linear model: μ_y = μ_y.dark + K (μ_e + μ_d);
  // σ²_y = K² (μ_e + μ_d + σ²_read + σ²_dsnu + σ²_row + σ²_col + (PRNU μ_e)² + var of μ_e) + 1/12.
  const double predictedMean = spec.blackLevelDn + K * (muE + dark);
  const double prnu = spec.prnuFraction * muE;
  const double predictedVar =
      K * K *
          (muE + dark + spec.readNoiseE * spec.readNoiseE + spec.dsnuE * spec.dsnuE +
           spec.rowFpnE * spec.rowFpnE + spec.columnFpnE * spec.columnFpnE + prnu * prnu + varE) +
      1.0 / 12.0;
  EXPECT_GT(muE, 100.0);
  EXPECT_LT(muE, 1000.0);  // a low light level: shot and read noise dominate
  // Tolerance 3 % (the issue's): the relative σ of a variance estimate over n ≈ 25000
  // samples is √(2/n) ≈ 0.9 %; the mean is known far better.
  EXPECT_NEAR((muDn - spec.blackLevelDn) / (predictedMean - spec.blackLevelDn), 1.0, 0.03);
  EXPECT_NEAR(varDn / predictedVar, 1.0, 0.03) << "n " << n << " muE " << muE << " varE " << varE;
  std::printf("flat patch: n %d, mu_e %.1f, mean ratio %.4f, variance ratio %.4f\n", n, muE,
              (muDn - spec.blackLevelDn) / (predictedMean - spec.blackLevelDn),
              varDn / predictedVar);
}

TEST(SensorRender, AutoExposurePutsTheMeanAtTheTarget) {
  Image electrons(4, 4, {"e"});
  for (size_t i = 0; i < electrons.pixels.size(); ++i)
    electrons.pixels[i] = static_cast<float>(10 + i);
  AutoExposure ae;  // mean, target 0.18
  const double k = autoExposureScale(electrons, ae, 6000.0);
  EXPECT_NEAR(meterElectrons(electrons, ae) * k, 0.18 * 6000.0, 1e-9);
  ae.metering = AutoExposure::Metering::kPercentile;
  ae.percentile = 100.0;
  ae.target = 0.9;
  EXPECT_NEAR(autoExposureScale(electrons, ae, 6000.0) * 25.0, 0.9 * 6000.0, 1e-9);  // max is 25
}

}  // namespace
}  // namespace camsim

namespace camsim {
namespace {

// `bracket_ev: [-1, 0, 1]` writes one DNG and raw EXR per frame; with noise off each stop
// doubles the signal above black (within DN rounding).
TEST(SensorRender, BracketWritesOneFramePerStop) {
  const test::TempDir temp;
  const std::filesystem::path& dir = temp.path();
  std::string scene = kFlatField;
  scene.replace(scene.find("noise: full, noise_seed: 9}"), 27,
                "noise: none, bracket_ev: [-1, 0, 1]}");
  scene.replace(scene.find("resolution: [256, 256]"), 22, "resolution: [32, 32]");
  test::writeFile(dir / "bracket.yaml", scene);
  const test::RunResult r =
      test::runCamsim("render " + test::quote((dir / "bracket.yaml").string()) + " -o " +
                          test::quote((dir / "out").string()) + " --spp 4",
                      dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  double previous = 0.0;
  for (const char* ev : {"-1", "+0", "+1"}) {
    const auto stem = dir / "out" / (std::string("bracket_ev") + ev);
    ASSERT_TRUE(std::filesystem::exists(stem.string() + ".dng")) << stem;
    const ExrFile raw = readExr(stem.string() + "_raw.exr");
    const int c = raw.image.channelIndex("raw.DN");
    ASSERT_GE(c, 0);
    double sum = 0.0;
    for (int y = 0; y < raw.image.height; ++y)
      for (int x = 0; x < raw.image.width; ++x)
        sum += static_cast<double>(raw.image.at(x, y, c)) - 64.0;
    const double mean = sum / (raw.image.width * raw.image.height);
    if (previous > 0.0) {
      EXPECT_NEAR(mean / previous, 2.0, 0.02) << ev;
    }
    previous = mean;
  }
}

}  // namespace
}  // namespace camsim
