// Tests for sensor/spectral_data: CSV spectral tables and the embedded CIE illuminants.
#include "sensor/spectra/spectral_data.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

// Parses text that must be rejected; returns the reported line (-1 if it did not throw).
int errorLine(const std::string& text) {
  try {
    parseSpectralCsv(text, "test.csv");
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "test.csv");
    return e.where().line;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return -1;
}

TEST(ParseSpectralCsv, ParsesAWellFormedTable) {
  const std::string text =
      "# a comment line\n"
      "wavelength_nm, r , g\n"
      "400,0.1,1\r\n"
      "\n"
      "# another comment\n"
      "450.5, +0.2 ,2e0\n"
      "500,-3.5e-1,3";  // no final newline
  const SpectralTable t = parseSpectralCsv(text, "good.csv");
  EXPECT_EQ(t.source, "good.csv");
  ASSERT_EQ(t.columns.size(), 2u);
  EXPECT_EQ(t.columns[0], "r");
  EXPECT_EQ(t.columns[1], "g");
  ASSERT_EQ(t.wavelengthsNm.size(), 3u);
  EXPECT_EQ(t.wavelengthsNm[0], 400.0);
  EXPECT_EQ(t.wavelengthsNm[1], 450.5);
  EXPECT_EQ(t.wavelengthsNm[2], 500.0);
  ASSERT_EQ(t.values.size(), 2u);
  ASSERT_EQ(t.values[0].size(), 3u);
  ASSERT_EQ(t.values[1].size(), 3u);
  // from_chars is correctly rounded: the doubles equal the literals exactly.
  EXPECT_EQ(t.values[0][0], 0.1);
  EXPECT_EQ(t.values[0][1], 0.2);
  EXPECT_EQ(t.values[0][2], -0.35);
  EXPECT_EQ(t.values[1][0], 1.0);
  EXPECT_EQ(t.values[1][1], 2.0);
  EXPECT_EQ(t.values[1][2], 3.0);
  EXPECT_EQ(t.columnIndex("r"), 0u);
  EXPECT_EQ(t.columnIndex("g"), 1u);
}

TEST(ParseSpectralCsv, SpectrumOfAColumn) {
  const SpectralTable t = parseSpectralCsv("nm,a\n400,1\n500,3\n", "t.csv");
  const Spectrum zero = t.spectrum(0, Extrapolation::kZero);
  const Spectrum clamp = t.spectrum(0, Extrapolation::kClamp);
  EXPECT_NEAR(static_cast<double>(zero.sample(450 - kLambdaMinNm)), 2.0, 1e-6);  // float storage
  EXPECT_EQ(zero.sample(399 - kLambdaMinNm), 0.0f);
  EXPECT_EQ(clamp.sample(399 - kLambdaMinNm), 1.0f);
  EXPECT_EQ(clamp.sample(501 - kLambdaMinNm), 3.0f);
}

TEST(ParseSpectralCsv, HeaderMissing) {
  // A header needs a wavelength column and a value column.
  EXPECT_EQ(errorLine("wavelength_nm\n400\n"), 1);
  EXPECT_EQ(errorLine("# c\n\nwavelength_nm\n400\n"), 3);
  // Empty column name.
  EXPECT_EQ(errorLine("wavelength_nm,a,\n400,1,2\n"), 1);
  // The first line is a data row: there is no header (the row must not be swallowed as
  // one with a column named "0.5").
  EXPECT_EQ(errorLine("400,0.5\n500,0.6\n"), 1);
  EXPECT_EQ(errorLine("# comment\n400,0.5\n500,0.6\n"), 2);
}

TEST(ParseSpectralCsv, RowWithWrongFieldCount) {
  EXPECT_EQ(errorLine("nm,a,b\n400,1,2\n500,1\n"), 3);
  EXPECT_EQ(errorLine("nm,a,b\n400,1,2\n# c\n500,1,2,3\n"), 4);
  EXPECT_EQ(errorLine("nm,a\n400,1,\n"), 2);  // trailing comma is an extra (empty) field
}

// Found by probing: `column: a` read the first of two columns named a, silently.
TEST(ParseSpectralCsv, ColumnNamedTwice) {
  EXPECT_EQ(errorLine("nm,a,b,a\n400,1,2,3\n"), 1);
}

TEST(ParseSpectralCsv, NonNumber) {
  EXPECT_EQ(errorLine("nm,a\n400,1\n500,abc\n"), 3);
  EXPECT_EQ(errorLine("nm,a\n400,1\nfive hundred,2\n"), 3);
  EXPECT_EQ(errorLine("nm,a\n400,1x\n"), 2);
  EXPECT_EQ(errorLine("nm,a\n400,\n"), 2);
  EXPECT_EQ(errorLine("nm,a\n400,1\n500,1e999\n"), 3);  // out of range for double
}

TEST(ParseSpectralCsv, NanAndInfinity) {
  EXPECT_EQ(errorLine("nm,a\n400,1\n500,nan\n"), 3);
  EXPECT_EQ(errorLine("nm,a\n400,1\n500,NaN\n"), 3);
  EXPECT_EQ(errorLine("nm,a\n400,inf\n"), 2);
  EXPECT_EQ(errorLine("nm,a\n400,-inf\n"), 2);
  EXPECT_EQ(errorLine("nm,a\n400,1\ninf,1\n"), 3);
  EXPECT_EQ(errorLine("nm,a\nnan,1\n"), 2);
}

TEST(ParseSpectralCsv, NonPositiveWavelength) {
  EXPECT_EQ(errorLine("nm,a\n0,1\n"), 2);
  EXPECT_EQ(errorLine("nm,a\n-400,1\n"), 2);
}

TEST(ParseSpectralCsv, NonIncreasingWavelengths) {
  EXPECT_EQ(errorLine("nm,a\n400,1\n500,1\n500,2\n"), 4);  // equal
  EXPECT_EQ(errorLine("nm,a\n400,1\n500,1\n450,2\n"), 4);  // decreasing
}

TEST(ParseSpectralCsv, HeaderOnly) {
  // No rows: the error points at the header that declares the empty table.
  EXPECT_EQ(errorLine("nm,a"), 1);
  EXPECT_EQ(errorLine("nm,a\n"), 1);
  EXPECT_EQ(errorLine("# c\nnm,a\n# c\n\n"), 2);
}

TEST(ParseSpectralCsv, EmptyText) {
  // No header at all: no line to point at (0 = unknown).
  EXPECT_EQ(errorLine(""), 0);
  EXPECT_EQ(errorLine("\n\n  \n"), 0);
  EXPECT_EQ(errorLine("# only a comment\n"), 0);
}

TEST(SpectralTable, ColumnIndexOfAMissingColumnThrows) {
  const SpectralTable t = parseSpectralCsv("nm,a,b\n400,1,2\n", "t.csv");
  try {
    (void)t.columnIndex("c");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "t.csv");
    const std::string what = e.what();
    EXPECT_NE(what.find("'c'"), std::string::npos) << what;
    EXPECT_NE(what.find("a, b"), std::string::npos) << what;  // lists the columns
  }
}

TEST(ReadSpectralCsv, ReadsAFileAndReportsItsPath) {
  const test::TempDir temp;
  const std::filesystem::path& dir = temp.path();
  const std::filesystem::path good = dir / "good.csv";
  const std::filesystem::path bad = dir / "bad.csv";
  std::ofstream(good) << "nm,v\n400,0.5\n410,0.25\n";
  std::ofstream(bad) << "nm,v\n400,0.5\n390,0.25\n";
  const SpectralTable t = readSpectralCsv(good);
  EXPECT_EQ(t.source, good.string());
  ASSERT_EQ(t.wavelengthsNm.size(), 2u);
  EXPECT_EQ(t.values[0][1], 0.25);
  try {
    readSpectralCsv(bad);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, bad.string());
    EXPECT_EQ(e.where().line, 3);
  }
  EXPECT_THROW(readSpectralCsv(dir / "missing.csv"), InputError);
}

TEST(CieIlluminant, D65IsNormalisedTo100At560Nm) {
  const Spectrum d65 = cieIlluminant("D65");
  EXPECT_EQ(d65.sample(560 - kLambdaMinNm), 100.0f);
  // Tabulated 5 nm values (CIE 15:2004): 555 nm 102.023, 565 nm 98.1671; 1e-4 (float).
  EXPECT_NEAR(static_cast<double>(d65.sample(555 - kLambdaMinNm)), 102.023, 1e-4);
  EXPECT_NEAR(static_cast<double>(d65.sample(565 - kLambdaMinNm)), 98.1671, 1e-4);
  // 1 nm samples between table points are the linear interpolation: (100 + 98.1671)/2.
  EXPECT_NEAR(static_cast<double>(d65(562.5f)), (100.0 + 98.1671) / 2.0, 1e-4);
}

TEST(CieIlluminant, AllNamedIlluminantsLoad) {
  for (const std::string& name : cieIlluminantNames()) {
    const Spectrum s = cieIlluminant(name);
    EXPECT_GE(s.minValue(), 0.0) << name;
    EXPECT_GT(s.sample(560 - kLambdaMinNm), 0.0f) << name;
    EXPECT_FALSE(embeddedSpectralFile("illuminants/illuminant_" + name + ".csv").empty()) << name;
  }
  // A, D50 and D65 are normalised to 100 at 560 nm.
  EXPECT_EQ(cieIlluminant("A").sample(560 - kLambdaMinNm), 100.0f);
  EXPECT_EQ(cieIlluminant("D50").sample(560 - kLambdaMinNm), 100.0f);
}

TEST(CieIlluminant, UnknownNameThrows) {
  EXPECT_THROW(cieIlluminant("D66"), InputError);
  EXPECT_THROW(cieIlluminant(""), InputError);
  EXPECT_THROW(cieIlluminant("../cie1931_2deg_xyz"), InputError);
  EXPECT_TRUE(embeddedSpectralFile("no/such/file.csv").empty());
}

}  // namespace
}  // namespace camsim
