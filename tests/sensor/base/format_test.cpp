// Tests for sensor/base/format: the shared number formatting of reports and metadata.
#include "sensor/base/format.h"

#include <gtest/gtest.h>

namespace camsim {
namespace {

TEST(Format, NumbersFixedAndRates) {
  EXPECT_EQ(formatNumber(0.000123456), "0.000123");
  EXPECT_EQ(formatNumber(2.0 / 3.0, 9), "0.666666667");
  EXPECT_EQ(formatFixed(1.005, 2), "1.00");  // 1.005 is stored as 1.00499999…, as printf
  EXPECT_EQ(formatFixed(-2.5, 0), "-2");     // round half to even, as printf
  EXPECT_EQ(formatRate(12345678.0), "12.35 M");
  EXPECT_EQ(formatRate(999999.0), "1000.00 k");  // below 1e6 stays in k
  EXPECT_EQ(formatRate(4200.0), "4.20 k");
  EXPECT_EQ(formatSize(512, 213), "512x213");
  EXPECT_EQ(formatRate(17.0), "17.00 ");
}

// Zero-padded to six digits, never cut: the exports' ids and the dataset's item folders.
TEST(Format, SixDigits) {
  EXPECT_EQ(formatSixDigits(0), "000000");
  EXPECT_EQ(formatSixDigits(42), "000042");
  EXPECT_EQ(formatSixDigits(1234567), "1234567");
}

}  // namespace
}  // namespace camsim
