// Tests of sensor/measure/mtf_measurement.h: luminance weights from primaries (Rec.709's
// and AP1's published Y rows), the channel selection, reading EXR and PNG files, and the
// CSV, JSON and summary texts of a measurement.
#include "sensor/measure/mtf_measurement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/png_io.h"
#include "sensor/spectra/color_space.h"
#include "tests/support/slanted_edge_image.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace mtf_measurement_test {

TEST(MtfMeasurement, LuminanceWeightsFromPrimaries) {
  const std::array<double, 3> rec709 = rec709LuminanceWeights();
  EXPECT_NEAR(rec709[0], 0.2126, 1e-4);
  EXPECT_NEAR(rec709[1], 0.7152, 1e-4);
  EXPECT_NEAR(rec709[2], 0.0722, 1e-4);
  // ACEScg (AP1, ACES white): S-2014-004's Y row 0.2722287, 0.6740818, 0.0536895.
  const RgbColorSpace& ap1 = RgbColorSpace::acesCg();
  const std::array<double, 3> w = luminanceWeights(ap1.red(), ap1.green(), ap1.blue(), ap1.white());
  EXPECT_NEAR(w[0], 0.2722287, 1e-6);
  EXPECT_NEAR(w[1], 0.6740818, 1e-6);
  EXPECT_NEAR(w[2], 0.0536895, 1e-6);
}

TEST(MtfMeasurement, SelectsChannelsByName) {
  Image rgb(2, 1, {"R", "G", "B", "XYZ.Y"});
  for (int c = 0; c < 4; ++c) rgb.at(1, 0, c) = static_cast<float>(c + 1);
  const std::array<double, 3> w{0.25, 0.5, 0.25};
  const Image all = selectMtfChannels(rgb, "all", w, "a.exr");
  EXPECT_EQ(all.channels, (std::vector<std::string>{"R", "G", "B", "Y"}));
  EXPECT_FLOAT_EQ(all.at(1, 0, 3), 0.25f * 1 + 0.5f * 2 + 0.25f * 3);
  EXPECT_FLOAT_EQ(all.at(1, 0, 1), 2.0f);
  EXPECT_EQ(selectMtfChannels(rgb, "G,B,G", w, "a.exr").channels,
            (std::vector<std::string>{"G", "B"}));
  EXPECT_EQ(selectMtfChannels(rgb, "XYZ.Y", w, "a.exr").channels,
            (std::vector<std::string>{"XYZ.Y"}));
  const Image grey(2, 1, {"L"});
  EXPECT_EQ(selectMtfChannels(grey, "all", w, "g.png").channels, (std::vector<std::string>{"Y"}));
  for (const char* bad : {"Q", "", "R,,G", "all,Z"}) {
    try {
      selectMtfChannels(rgb, bad, w, "a.exr");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "channel");
      EXPECT_EQ(e.where().file, "a.exr");
      EXPECT_NE(e.message().find("XYZ.Y"), std::string::npos) << e.message();  // lists them
    }
  }
}

TEST(MtfMeasurement, ReadsExrAndPngFiles) {
  test::TempDir dir;
  Image img(2, 2, {"R", "G", "B"});
  img.at(0, 0, 1) = 0.5f;
  const RgbColorSpace& ap1 = RgbColorSpace::acesCg();
  writeExr(dir.path() / "a.exr", img, {},
           ExrChromaticities{ap1.red(), ap1.green(), ap1.blue(), ap1.white()});
  const MtfImage exr = readMtfImage(dir.path() / "a.exr", false);
  EXPECT_EQ(exr.format, "exr");
  EXPECT_FLOAT_EQ(exr.image.at(0, 0, exr.image.channelIndex("G")), 0.5f);
  EXPECT_NEAR(exr.yWeights[1], 0.6740818, 1e-6);  // from the file's chromaticities

  writePng(dir.path() / "g.png", PngImage{2, 1, 2, 8, {128, 255, 255, 0}});  // grey + alpha
  const MtfImage srgb = readMtfImage(dir.path() / "g.png", false);
  EXPECT_EQ(srgb.image.channels, (std::vector<std::string>{"Y"}));
  EXPECT_NEAR(srgb.image.at(0, 0, 0), srgbDecode(128.0 / 255.0), 1e-6);
  EXPECT_FLOAT_EQ(srgb.image.at(1, 0, 0), 1.0f);
  EXPECT_NEAR(readMtfImage(dir.path() / "g.png", true).image.at(0, 0, 0), 128.0 / 255.0, 1e-6);

  test::writeFile(dir.path() / "t.txt", "hello");
  for (const auto& [name, message] :
       {std::pair{"t.txt", "not an OpenEXR or PNG"}, std::pair{"missing.exr", "cannot open"}}) {
    try {
      readMtfImage(dir.path() / name, false);
      ADD_FAILURE() << name;
    } catch (const InputError& e) {
      EXPECT_NE(e.message().find(message), std::string::npos) << e.what();
      EXPECT_EQ(e.where().file, (dir.path() / name).string());
    }
  }
}

TEST(MtfMeasurement, CsvJsonAndSummary) {
  test::SyntheticEdge sharp;  // a perfect step, point-sampled: MTF above 0.5 to 1 cy/px
  sharp.size = 0.0;
  test::SyntheticEdge soft;  // σ = 0.5 px
  Image img(64, 128, {"G", "Y"});
  const Image a = test::syntheticEdgeImage(sharp), b = test::syntheticEdgeImage(soft);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 64; ++x) {
      img.at(x, y, 0) = a.at(x, y, 0);
      img.at(x, y, 1) = b.at(x, y, 0);
    }
  SfrOptions o;
  o.pixelPitchM = 1.4e-6;
  o.source = "edge.exr";
  const MtfMeasurement m = measureMtf(img, {0, 0, 64, 128}, o);
  ASSERT_EQ(m.channels.size(), 2u);
  EXPECT_EQ(m.reference().name, "Y");
  EXPECT_FALSE(m.channels[0].sfr.mtf50.has_value());

  const std::string csv = formatMtfCsv(m);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "frequency_cy_px,frequency_cy_mm,mtf_G,mtf_Y");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 66);            // header + 65 frequencies
  EXPECT_NE(csv.find("\n0.5,357.14286,"), std::string::npos) << csv;  // Nyquist at 1.4 µm

  const std::string json = formatMtfJson(m);
  for (const char* part :
       {"\"format\": \"camsim-mtf\"", "\"source\": \"edge.exr\"",
        "\"edge_orientation\": \"vertical\"", "\"mtf50_cy_px\": null", "\"mtf50_cy_mm\": null",
        "\"pixel_pitch_um\": 1.4", "\"misregistration_px\": 0,", "\"rows_used\": 126"})
    EXPECT_NE(json.find(part), std::string::npos) << part << "\n" << json;

  const std::string summary = formatMtfSummary(m);
  EXPECT_NE(summary.find("vertical edge at 5.00°, 126 rows along it"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("  G     MTF50 > 1 cy/px"), std::string::npos) << summary;
  EXPECT_NE(summary.find("  Y     MTF50 0.3695 cy/px (263.9 cy/mm)"), std::string::npos) << summary;
}

}  // namespace mtf_measurement_test
}  // namespace camsim
