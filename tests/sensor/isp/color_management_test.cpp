// Tests for sensor/color_management: the shipped luts/config.ocio, config resolution
// (explicit path > $OCIO > $CAMSIM_LUTS / CAMSIM_LUTS_DIR), name validation and the measured
// code values of ACEScg mid grey on the displays.
#include "sensor/isp/color_management.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "tests/support/env_guard.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

const fs::path kShipped = fs::path(CAMSIM_SOURCE_DIR) / "luts" / "config.ocio";

double d(float v) {
  return static_cast<double>(v);
}

// A tiny valid config: one display "TestDisplay" whose view "Square root" encodes linear
// values with an exponent 1/2; no colour space is called ACEScg, so scene_linear is the input.
constexpr const char* kTinyConfig = R"(ocio_profile_version: 2
search_path: ""
strictparsing: true
roles:
  default: linear
  scene_linear: linear
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  TestDisplay:
    - !<View> {name: Square root, colorspace: sqrt}
colorspaces:
  - !<ColorSpace> {name: linear, isdata: false}
  - !<ColorSpace>
    name: sqrt
    isdata: false
    from_scene_reference: !<ExponentTransform> {value: [2, 2, 2, 1], direction: inverse}
)";

// ACEScg → CIE XYZ D65 → gamma 2.6 P3-D65 with the library's builtins only: a reference for
// the Display P3 matrix of the shipped config, which OCIO 2.1 has no builtin for.
constexpr const char* kP3ReferenceConfig = R"(ocio_profile_version: 2.1
search_path: ""
strictparsing: true
roles:
  default: ACEScg
  scene_linear: ACEScg
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  P3 G2.6:
    - !<View> {name: Plain, view_transform: Plain, display_colorspace: p3g26}
view_transforms:
  - !<ViewTransform>
    name: Plain
    from_scene_reference: !<BuiltinTransform> {style: UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD}
display_colorspaces:
  - !<ColorSpace>
    name: p3g26
    from_display_reference: !<BuiltinTransform> {style: DISPLAY - CIE-XYZ-D65_to_G2.6-P3-D65}
colorspaces:
  - !<ColorSpace> {name: ACES2065-1}
  - !<ColorSpace>
    name: ACEScg
    to_scene_reference: !<BuiltinTransform> {style: ACEScg_to_ACES2065-1}
)";

class ColorManagementTest : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    test::writeFile(p, text);
    return p;
  }

  static int grey8(const OcioProcessor& ocio, const DisplayChoice& choice, float grey = 0.18f) {
    const auto rgb = ocio.pipeline(choice).applyPixel({grey, grey, grey});
    EXPECT_NEAR(d(rgb[0]), d(rgb[1]), 1e-4);  // a neutral stays neutral
    EXPECT_NEAR(d(rgb[2]), d(rgb[1]), 1e-4);
    return quantizeDisplay8(rgb)[1];
  }

  // $OCIO and $CAMSIM_LUTS are unset for every test and restored afterwards.
  test::EnvGuard ocioEnv_{"OCIO"};
  test::EnvGuard lutsEnv_{"CAMSIM_LUTS"};
  test::TempDir tmp_;
  fs::path dir_ = tmp_.path();
};

TEST_F(ColorManagementTest, ShippedConfigLoadsByDefault) {
  const OcioProcessor ocio;
  EXPECT_EQ(ocio.location().origin, OcioConfigOrigin::Camsim);
  EXPECT_EQ(fs::canonical(ocio.location().path), fs::canonical(kShipped));
  EXPECT_EQ(ocio.inputColorSpace(), "ACEScg");
  EXPECT_EQ(ocio.displays(),
            (std::vector<std::string>{"sRGB", "Rec.1886 Rec.709", "Display P3", "Rec.2100-PQ"}));
  EXPECT_EQ(ocio.defaultDisplay(), "sRGB");
  EXPECT_EQ(ocio.defaultView("sRGB"), "ACES 1.0 - SDR Video");
  EXPECT_EQ(ocio.views("sRGB"),
            (std::vector<std::string>{"ACES 1.0 - SDR Video", "Un-tone-mapped", "Raw"}));
  EXPECT_EQ(ocio.defaultView("Rec.2100-PQ"), "ACES 1.1 - HDR Video (1000 nits & P3 lim)");
  EXPECT_EQ(ocio.looks(), std::vector<std::string>{"camsim warm"});
  const DisplayChoice resolved = ocio.resolve({});
  EXPECT_EQ(resolved.display, "sRGB");
  EXPECT_EQ(resolved.view, "ACES 1.0 - SDR Video");
}

TEST_F(ColorManagementTest, EveryDisplayViewAndLookBuildsACpuProcessor) {
  const OcioProcessor ocio;
  int pairs = 0;
  for (const std::string& display : ocio.displays()) {
    for (const std::string& view : ocio.views(display)) {
      for (const std::string looks : {"", "camsim warm"}) {
        if (view == "Raw" && !looks.empty()) continue;  // a data view takes no look
        SCOPED_TRACE(display + " / " + view + " / " + looks);
        const DisplayPipeline pipe = ocio.pipeline({display, view, looks});
        EXPECT_EQ(pipe.choice().display, display);
        std::vector<float> rgb{0.18f, 0.18f, 0.18f, 1.0f, 0.5f, 0.1f, 0.0f, 0.0f, 0.0f};
        pipe.applyInPlace(rgb, 3, 1);
        for (float v : rgb) EXPECT_TRUE(std::isfinite(v));
        EXPECT_GT(rgb[1], 0.0f);
      }
      ++pairs;
    }
  }
  EXPECT_EQ(pairs, 13);
}

// Every display and view, grey from 1 to the largest float: finite and never darker for
// brighter input (found by probing: the ACES SDR view gave black at 1e25 and 1e30 between
// white at 1e20 and 1e35; the un-tone-mapped view inf at 3e38).
TEST_F(ColorManagementTest, BrighterInputIsNeverDarkerAndAlwaysFinite) {
  const OcioProcessor ocio;
  for (const std::string& display : ocio.displays())
    for (const std::string& view : ocio.views(display)) {
      if (view == "Raw") continue;  // data: no transform
      SCOPED_TRACE(display + " / " + view);
      const DisplayPipeline pipe = ocio.pipeline({display, view, ""});
      float previous = -1.0f;
      const float inf = std::numeric_limits<float>::infinity();  // black by inf·0 (review)
      for (const float grey :
           {1.0f, 1e3f, 1e6f, 1e9f, 1e10f, 1e12f, 1e20f, 1e25f, 1e30f, 3e38f, inf}) {
        const std::array<float, 3> out = pipe.applyPixel({grey, grey, grey});
        for (float v : out) ASSERT_TRUE(std::isfinite(v)) << grey;
        EXPECT_GE(out[1], previous * (1.0f - 1e-5f)) << grey;
        previous = out[1];
      }
    }
}

TEST_F(ColorManagementTest, MidGreyCodeValues) {
  const OcioProcessor ocio;
  // Un-tone-mapped: display Y = 0.18, sRGB-encoded 0.4614 → 117.7.
  EXPECT_NEAR(grey8(ocio, {"sRGB", "Un-tone-mapped", ""}), 118, 1);
  // Display P3 has the sRGB curve and the same white: same code value.
  EXPECT_NEAR(grey8(ocio, {"Display P3", "Un-tone-mapped", ""}), 118, 1);
  // Rec.1886 (inverse gamma 2.4): 0.18^(1/2.4) = 0.4897 → 124.9.
  EXPECT_NEAR(grey8(ocio, {"Rec.1886 Rec.709", "Un-tone-mapped", ""}), 125, 1);
  // ACES 1.0 SDR video puts scene 0.18 at display Y = 0.104 (10.4 nits of 100), darker than
  // the un-tone-mapped 0.18: sRGB 0.356 → measured 91; a plausible ACES mid grey is 85 – 100.
  const int aces = grey8(ocio, {"sRGB", "ACES 1.0 - SDR Video", ""});
  EXPECT_GE(aces, 85);
  EXPECT_LE(aces, 100);
  EXPECT_EQ(aces, 91);
  // Scene 1.0 clips to white without tone mapping.
  EXPECT_EQ(grey8(ocio, {"sRGB", "Un-tone-mapped", ""}, 1.0f), 255);
  // The same display light on Rec.1886: 0.104^(1/2.4) = 0.390 → 99.
  EXPECT_EQ(grey8(ocio, {"Rec.1886 Rec.709", "ACES 1.0 - SDR Video", ""}), 99);
  // The data view passes values through.
  EXPECT_EQ(ocio.pipeline({"sRGB", "Raw", ""}).applyPixel({0.18f, 0.5f, 2.0f}),
            (std::array<float, 3>{0.18f, 0.5f, 2.0f}));
}

// ST 2084 EOTF: PQ code value [0, 1] → absolute luminance in cd/m².
double pqToNits(double e) {
  const double m1 = 2610.0 / 16384.0, m2 = 2523.0 / 4096.0 * 128.0;
  const double c1 = 3424.0 / 4096.0, c2 = 2413.0 / 4096.0 * 32.0, c3 = 2392.0 / 4096.0 * 32.0;
  const double p = std::pow(e, 1.0 / m2);
  return 10000.0 * std::pow(std::max(p - c1, 0.0) / (c2 - c3 * p), 1.0 / m1);
}

TEST_F(ColorManagementTest, HdrPqMidGreyIsFifteenNits) {
  const OcioProcessor ocio;
  const auto pq = ocio.pipeline({"Rec.2100-PQ", "", ""}).applyPixel({0.18f, 0.18f, 0.18f});
  // The 1000-nit ACES 1.1 output transform puts mid grey at 15 nits (its name says so).
  EXPECT_NEAR(pqToNits(d(pq[1])), 15.0, 0.5);
  // Un-tone-mapped on PQ: display reference 1.0 = 100 nits, so 0.18 → 18 nits.
  const auto flat =
      ocio.pipeline({"Rec.2100-PQ", "Un-tone-mapped", ""}).applyPixel({0.18f, 0.18f, 0.18f});
  EXPECT_NEAR(pqToNits(d(flat[1])), 18.0, 0.1);
}

TEST_F(ColorManagementTest, DisplayP3MatrixMatchesTheBuiltinP3D65) {
  // Linear P3-D65 light must be the same through the shipped Display P3 (matrix + sRGB curve)
  // and through the builtin gamma-2.6 P3-D65 display; only the curve differs.
  const OcioProcessor shipped;
  const OcioProcessor reference(write("p3.ocio", kP3ReferenceConfig));
  const DisplayPipeline p3 = shipped.pipeline({"Display P3", "Un-tone-mapped", ""});
  const DisplayPipeline g26 = reference.pipeline({"P3 G2.6", "Plain", ""});
  auto srgbDecode = [](float v) {
    const double e = d(v);
    return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
  };
  // Saturated colours inside P3 (the gamma-2.6 display clamps negative values).
  for (const std::array<float, 3>& acescg :
       {std::array<float, 3>{0.5f, 0.2f, 0.1f}, std::array<float, 3>{0.25f, 0.6f, 0.2f},
        std::array<float, 3>{0.2f, 0.25f, 0.6f}}) {
    const auto a = p3.applyPixel(acescg);
    const auto b = g26.applyPixel(acescg);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(srgbDecode(a[c]), std::pow(d(b[c]), 2.6), 2e-4) << acescg[0] << " " << c;
  }
}

TEST_F(ColorManagementTest, WarmLookWarmsGrey) {
  const OcioProcessor ocio;
  const auto plain = ocio.pipeline({"sRGB", "Un-tone-mapped", ""}).applyPixel({.18f, .18f, .18f});
  const auto warm =
      ocio.pipeline({"sRGB", "Un-tone-mapped", "camsim warm"}).applyPixel({.18f, .18f, .18f});
  EXPECT_GT(warm[0], plain[0] + 0.01f);
  EXPECT_LT(warm[2], plain[2] - 0.01f);
  EXPECT_NEAR(d(warm[1]), d(plain[1]), 0.01);
  // Look lists use OCIO's syntax.
  EXPECT_EQ(ocio.resolve({"", "", " +camsim warm "}).looks, "+camsim warm");
}

TEST_F(ColorManagementTest, ExplicitConfigIsUsedInsteadOfTheDefault) {
  const fs::path tiny = write("tiny.ocio", kTinyConfig);
  ::setenv("OCIO", kShipped.c_str(), 1);  // the explicit path wins over $OCIO
  const OcioProcessor ocio(tiny);
  EXPECT_EQ(ocio.location().origin, OcioConfigOrigin::Explicit);
  EXPECT_EQ(ocio.location().path, tiny);
  EXPECT_EQ(ocio.displays(), std::vector<std::string>{"TestDisplay"});
  EXPECT_EQ(ocio.inputColorSpace(), "linear");  // no ACEScg: the scene_linear role
  const auto rgb = ocio.pipeline({}).applyPixel({0.25f, 0.04f, 1.0f});
  EXPECT_NEAR(d(rgb[0]), 0.5, 1e-5);
  EXPECT_NEAR(d(rgb[1]), 0.2, 1e-5);
  EXPECT_NEAR(d(rgb[2]), 1.0, 1e-5);
}

TEST_F(ColorManagementTest, OcioEnvironmentVariableIsHonoured) {
  const fs::path tiny = write("tiny.ocio", kTinyConfig);
  ::setenv("OCIO", tiny.c_str(), 1);
  const OcioProcessor ocio;
  EXPECT_EQ(ocio.location().origin, OcioConfigOrigin::OcioEnvironment);
  EXPECT_EQ(ocio.displays(), std::vector<std::string>{"TestDisplay"});
  // An empty $OCIO is ignored.
  ::setenv("OCIO", "", 1);
  EXPECT_EQ(OcioProcessor().location().origin, OcioConfigOrigin::Camsim);
}

TEST_F(ColorManagementTest, CamsimLutsVariableLocatesTheDefaultConfig) {
  write("config.ocio", kTinyConfig);
  ::setenv("CAMSIM_LUTS", dir_.c_str(), 1);
  EXPECT_EQ(camsimOcioConfigPath(), dir_ / "config.ocio");
  const OcioProcessor ocio;
  EXPECT_EQ(ocio.location().origin, OcioConfigOrigin::Camsim);
  EXPECT_EQ(ocio.displays(), std::vector<std::string>{"TestDisplay"});
}

// The InputError message of f(), or "" if it does not throw one.
template <typename F>
std::string inputErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(ColorManagementTest, UnknownNamesThrowListingTheChoices) {
  const OcioProcessor ocio;
  const std::string display = inputErrorOf([&] { ocio.pipeline({"sRBG", "", ""}); });
  EXPECT_NE(display.find("unknown display 'sRBG'"), std::string::npos) << display;
  EXPECT_NE(display.find("'sRGB', 'Rec.1886 Rec.709', 'Display P3', 'Rec.2100-PQ'"),
            std::string::npos)
      << display;
  const std::string view = inputErrorOf([&] { ocio.pipeline({"sRGB", "Filmic", ""}); });
  EXPECT_NE(view.find("unknown view 'Filmic'"), std::string::npos) << view;
  EXPECT_NE(view.find("'ACES 1.0 - SDR Video', 'Un-tone-mapped', 'Raw'"), std::string::npos)
      << view;
  const std::string look = inputErrorOf([&] { ocio.pipeline({"", "", "camsim warm, cold"}); });
  EXPECT_NE(look.find("unknown look 'cold'"), std::string::npos) << look;
  EXPECT_NE(look.find("'camsim warm'"), std::string::npos) << look;
  EXPECT_NE(inputErrorOf([&] { ocio.views("nope"); }).find("'Display P3'"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] {
              ocio.pipeline({"sRGB", "Raw", "camsim warm"});
            }).find("looks cannot apply"),
            std::string::npos);
  // HDR view on an SDR display.
  EXPECT_NE(inputErrorOf([&] {
              ocio.resolve({"sRGB", "ACES 1.1 - HDR Video (1000 nits & P3 lim)", ""});
            }).find("unknown view"),
            std::string::npos);
}

TEST_F(ColorManagementTest, BadConfigsThrowInputError) {
  const std::string missing = inputErrorOf([&] { OcioProcessor(dir_ / "missing.ocio"); });
  EXPECT_NE(missing.find("missing.ocio"), std::string::npos) << missing;
  EXPECT_NE(missing.find("explicit path"), std::string::npos) << missing;
  ::setenv("OCIO", (dir_ / "gone.ocio").c_str(), 1);
  EXPECT_NE(inputErrorOf([] { OcioProcessor(); }).find("$OCIO"), std::string::npos);
  const fs::path garbage = write("garbage.ocio", "ocio_profile_version: 2\ncolorspaces: [1, 2\n");
  EXPECT_NE(inputErrorOf([&] { OcioProcessor{garbage}; }).find("invalid OCIO config"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { OcioProcessor(kShipped, "ACEScgg"); }).find("'ACEScct'"),
            std::string::npos);
}

TEST(Quantize, ClampsRoundsAndZeroesNaN) {
  const std::vector<float> v{-0.5f, 0.0f, 0.51f / 255.0f, 0.49f / 255.0f,
                             0.5f,  1.0f, 7.0f,           std::nanf("")};
  EXPECT_EQ(quantizeDisplay8(v), (std::vector<std::uint8_t>{0, 0, 1, 0, 128, 255, 255, 0}));
  EXPECT_EQ(quantizeDisplay16(v),
            (std::vector<std::uint16_t>{0, 0, 131, 126, 32768, 65535, 65535, 0}));
}

TEST_F(ColorManagementTest, OciocheckPassesOnTheShippedConfig) {
  if (test::runCommand("command -v ociocheck", dir_).exitCode != 0)
    GTEST_SKIP() << "ociocheck is not on PATH";
  const test::RunResult r =
      test::runCommand("ociocheck --iconfig " + test::quote(kShipped.string()), dir_);
  const std::string text = r.out + r.err;
  EXPECT_EQ(r.exitCode, 0) << text;
  EXPECT_NE(text.find("passed"), std::string::npos) << text;
  EXPECT_EQ(text.find("ERROR"), std::string::npos) << text;
  EXPECT_EQ(text.find("WARNING"), std::string::npos) << text;
}

}  // namespace
}  // namespace camsim
