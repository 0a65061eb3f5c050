// Lens prescription files: pbrt-v4's three files read in SI; the key=value extension; every
// kind of bad input an InputError naming the file, the line, the column and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "integrator/camera/lens_file.h"
#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"
#include "tests/integrator/lens_test_support.h"

namespace camsim {
namespace lens_file_test {

TEST(LensFile, ReadsPbrtFilesInMetres) {
  struct Case {
    const char* file;
    size_t surfaces;
    int stop;
    double firstRadiusMm, stopApertureMm;
  };
  for (const Case& c : {Case{"dgauss.50mm.dat", 11, 5, 29.475, 17.1},
                        Case{"fisheye.10mm.dat", 12, 6, 30.2249, 6.08},
                        Case{"telephoto.250mm.dat", 7, 3, 54.6275, 40.5}}) {
    const LensPrescription lens = readLensPrescription(test::lensPath(c.file));
    ASSERT_EQ(lens.surfaces.size(), c.surfaces) << c.file;
    EXPECT_EQ(lens.stopIndex, c.stop) << c.file;
    EXPECT_DOUBLE_EQ(lens.surfaces[0].radius, c.firstRadiusMm * 1e-3) << c.file;
    const LensSurface& stop = lens.surfaces[static_cast<size_t>(c.stop)];
    EXPECT_TRUE(stop.stop);
    EXPECT_DOUBLE_EQ(stop.apertureDiameter, c.stopApertureMm * 1e-3) << c.file;
    EXPECT_EQ(stop.medium.model(), GlassModel::kAir) << c.file;
    // No glass named: the indices do not disperse (pbrt-v4's behaviour).
    for (const LensSurface& s : lens.surfaces) {
      EXPECT_FALSE(s.medium.disperses());
      EXPECT_FALSE(s.aspheric());
    }
    EXPECT_EQ(lens.surfaces.back().medium.nd(), 1.0);
  }
  const LensPrescription dgauss = readLensPrescription(test::lensPath("dgauss.50mm.dat"));
  EXPECT_DOUBLE_EQ(dgauss.surfaces[3].thickness, 3.275e-3);
  EXPECT_DOUBLE_EQ(dgauss.surfaces[3].medium.nd(), 1.699);
  EXPECT_EQ(dgauss.surfaces[3].line, 9);  // after five comment lines
}

TEST(LensFile, ExtensionKeysConvertToSi) {
  const std::string text =
      "# radius thickness N aperture, then keys\r\n"
      "\n"
      "+40  4  1.5168  20  glass=BK7 conic=-0.5 a4=1e-5 a6=-2e-8 a16=1e-30  # a comment\r\n"
      "-200 2  1       20\n"
      "0    3  0       12\n"
      "-60  3  1.62    18  abbe=36.37\n"
      "0    0  1       18\n";
  const LensPrescription lens = parseLensPrescription(text, "ext.dat");
  ASSERT_EQ(lens.surfaces.size(), 5u);
  const LensSurface& s = lens.surfaces[0];
  EXPECT_EQ(s.line, 3);
  EXPECT_DOUBLE_EQ(s.radius, 0.040);
  EXPECT_DOUBLE_EQ(s.conic, -0.5);
  // a_{2i} mm^(1−2i) → m^(1−2i): times 1000^(2i−1).
  EXPECT_NEAR(s.asphere[0], 1e-5 * 1e9, 1e-12 * 1e4);
  EXPECT_NEAR(s.asphere[1], -2e-8 * 1e15, 1e-12 * 2e7);
  EXPECT_NEAR(s.asphere[6], 1e-30 * 1e45, 1e-12 * 1e15);
  EXPECT_TRUE(s.aspheric());
  EXPECT_EQ(s.medium.model(), GlassModel::kTable);
  EXPECT_EQ(s.medium.name(), "BK7");
  EXPECT_DOUBLE_EQ(s.medium.index(kLambdaDNm), 1.5168);
  EXPECT_EQ(lens.surfaces[3].medium.model(), GlassModel::kAbbe);
  EXPECT_NEAR(lens.surfaces[3].medium.abbeNumber(), 36.37, 1e-9);
  EXPECT_EQ(lens.surfaces[4].radius, 0.0);  // a plane
  EXPECT_FALSE(lens.surfaces[4].stop);
}

TEST(LensFile, GlassTablesAreLookedUpOnTheSearchPathAndRecorded) {
  std::vector<std::filesystem::path> read;
  TableSearch search{{lutsDirectory() / "spectra"}, &read};
  parseLensPrescription(
      "40 4 1.5168 20 glass=BK7\n0 1 0 10\n-40 0 1.6 20 glass=BK7\n"
      "-100 0 1 20\n",
      "g.dat", search);
  ASSERT_EQ(read.size(), 1u);  // read once for two lines
  EXPECT_EQ(read[0].filename(), "BK7.csv");
}

struct BadCase {
  std::string text;
  int line;
  int column;
  std::string key;
  std::string message;  // a part of it
};

TEST(LensFile, BadInputNamesFileLineColumnAndKey) {
  const std::string stop = "0 5 0 10\n";
  const std::string rear = "-50 0 1 20\n";
  const std::vector<BadCase> cases = {
      {"abc 2 1.5 20\n" + stop + rear, 1, 1, "radius", "no number"},
      {"nan 2 1.5 20\n" + stop + rear, 1, 1, "radius", "finite"},
      {"50 inf 1.5 20\n" + stop + rear, 1, 4, "thickness", "finite"},
      {"50 -1 1.5 20\n" + stop + rear, 1, 4, "thickness", "≥ 0"},
      {"50 2 1.5 -20\n" + stop + rear, 1, 10, "aperture", "> 0"},
      {"50 2 1.5 0\n" + stop + rear, 1, 10, "aperture", "> 0"},
      {"50 2 0.5 20\n" + stop + rear, 1, 6, "N", "[1, 3]"},
      {"50 2 1.5\n" + stop + rear, 1, 6, "aperture", "4 columns"},
      {"50 2 1.5 20\n10 5 0 10\n" + rear, 2, 1, "radius", "stop"},
      {"50 2 1.5 20\n" + rear, 0, 0, "", "no aperture stop"},
      {"50 2 1.5 20\n" + stop + stop + rear, 3, 5, "N", "second aperture stop"},
      {"50 2 1.5 20 foo=1\n" + stop + rear, 1, 13, "foo", "unknown key"},
      {"50 2 1.5 20 glass=NOPE\n" + stop + rear, 1, 13, "glass", "unknown glass 'NOPE'"},
      {"50 2 1.5 20 glass=../BK7\n" + stop + rear, 1, 13, "glass", "no glass name"},
      {"50 2 1.5 20 glass=BK7 abbe=60\n" + stop + rear, 1, 23, "abbe", "either"},
      {"50 2 1 20 abbe=60\n" + stop + rear, 1, 11, "abbe", "air"},
      {"50 2 1.5 20 abbe=2\n" + stop + rear, 1, 13, "abbe", "[5, 200]"},
      {"50 2 3 20 abbe=5\n" + stop + rear, 1, 11, "abbe", "leaves [1, 4] at 360 nm"},
      {"50 2 1.5 20 conic=1 conic=2\n" + stop + rear, 1, 21, "conic", "twice"},
      {"50 2 1.5 20 conic=x\n" + stop + rear, 1, 13, "conic", "no number"},
      {"50 2 1.5 20 a4=1e300\n" + stop + rear, 1, 13, "a4", "too large"},
      {"50 2 1.5 20 3\n" + stop + rear, 1, 13, "", "key=value"},
      // Numbers in their shortest form (%f gave "9.000000", and 300 digits for 1e300).
      {"9 2 1.5 20\n" + stop + rear, 1, 1, "radius",
       "clear aperture (radius 9 mm, aperture 20 mm)"},
      {"20 2 1.5 20 conic=5\n" + stop + rear, 1, 13, "conic", "clear aperture"},
      {"50 2 1.5 20\n0 5 0 10 conic=1\n" + rear, 2, 10, "conic", "stop takes no keys"},
      {"50 2 1.5 20\n" + stop + "-50 0 1.5 20\n", 3, 0, "N", "air"},
      {"# only a comment\n\n", 0, 0, "", "no surfaces"},
  };
  for (const BadCase& c : cases) {
    try {
      parseLensPrescription(c.text, "bad.dat");
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "bad.dat");
      EXPECT_EQ(e.where().line, c.line) << e.what();
      EXPECT_EQ(e.where().column, c.column) << e.what();
      EXPECT_EQ(e.key(), c.key) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
      if (c.line > 0) {
        EXPECT_EQ(std::string(e.what()).rfind("bad.dat:" + std::to_string(c.line) + ":", 0), 0u)
            << e.what();
      }
    }
  }
}

TEST(LensFile, TooManySurfacesAndMissingFile) {
  std::string text = "0 1 0 10\n";
  for (int i = 0; i < kMaxLensSurfaces; ++i) text += "0 1 1 10\n";
  try {
    parseLensPrescription(text, "long.dat");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, kMaxLensSurfaces + 1);
  }
  try {
    readLensPrescription("/nonexistent/lens.dat");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "/nonexistent/lens.dat");
  }
}

}  // namespace lens_file_test
}  // namespace camsim
