// Glass dispersion: the Abbe model holds n_d and n_F − n_C exactly; the catalogue table
// through its spline against Schott's Sellmeier formula; no dispersion by default.
#include <gtest/gtest.h>

#include <cmath>

#include "integrator/camera/glass.h"
#include "integrator/camera/lens_file.h"

namespace camsim {
namespace glass_test {

// Schott's Sellmeier formula for N-BK7 (λ in µm), the source of luts/spectra/glasses/BK7.csv.
double sellmeierBk7(double lambdaNm) {
  const double l2 = lambdaNm * lambdaNm * 1e-6;
  return std::sqrt(1.0 + 1.03961212 * l2 / (l2 - 0.00600069867) +
                   0.231792344 * l2 / (l2 - 0.0200179144) + 1.01046945 * l2 / (l2 - 103.560653));
}

Glass bk7(double nd) {
  const LensPrescription lens = parseLensPrescription(
      "40 4 " + std::to_string(nd) + " 20 glass=BK7\n0 1 0 10\n-40 0 1 20\n", "bk7.dat");
  return lens.surfaces[0].medium;
}

TEST(Glass, AbbeModelHoldsIndexAndAbbeNumberExactly) {
  for (const auto& [nd, v] : {std::pair{1.5168, 64.17}, {1.7847, 25.72}, {1.4970, 81.61}}) {
    const Glass g = Glass::abbe(nd, v);
    EXPECT_NEAR(g.index(kLambdaDNm), nd, 1e-14);
    EXPECT_NEAR(g.index(kLambdaFNm) - g.index(kLambdaCNm), (nd - 1.0) / v, 1e-14);
    EXPECT_NEAR(g.abbeNumber(), v, 1e-9);
    EXPECT_TRUE(g.disperses());
    EXPECT_GT(g.index(400.0), g.index(700.0));  // normal dispersion
  }
}

TEST(Glass, CatalogueTableFollowsSellmeier) {
  // With the glass's own n_d (Schott: 1.5168) the shift is the table's rounding.
  const Glass g = bk7(1.5168);
  EXPECT_EQ(g.model(), GlassModel::kTable);
  EXPECT_DOUBLE_EQ(g.index(kLambdaDNm), 1.5168);
  // The natural cubic spline through the 22 nm table stays within 2e-5 of the formula
  // (linear interpolation errs by up to 3e-5 near 486 nm); the table itself rounds to 5e-6.
  double worst = 0.0;
  for (double lambda = 380.0; lambda <= 800.0; lambda += 0.5)
    worst = std::max(worst, std::abs(g.index(lambda) - sellmeierBk7(lambda)));
  EXPECT_LT(worst, 2e-5);
  // Schott's V_d for N-BK7 is 64.17; the formula gives 64.14 at these lines.
  EXPECT_NEAR(g.abbeNumber(), 64.17, 0.1);
  // A named glass lends its dispersion to another n_d: n_d moves, n(λ) − n_d does not.
  const Glass shifted = bk7(1.6);
  EXPECT_DOUBLE_EQ(shifted.index(kLambdaDNm), 1.6);
  EXPECT_NEAR(shifted.index(450.0) - 1.6, g.index(450.0) - 1.5168, 1e-12);
  // Outside the table (SF10 starts at 380 nm) n holds the end value.
  const Glass sf10 =
      parseLensPrescription("40 4 1.728 20 glass=SF10\n0 1 0 10\n-40 0 1 20\n", "sf10.dat")
          .surfaces[0]
          .medium;
  EXPECT_DOUBLE_EQ(sf10.index(360.0), sf10.index(380.0));
  EXPECT_GT(sf10.index(380.0), sf10.index(381.0));
}

TEST(Glass, WithoutGlassOrAbbeThereIsNoDispersion) {
  const Glass c = Glass::constant(1.67);
  EXPECT_FALSE(c.disperses());
  EXPECT_EQ(c.index(400.0), 1.67);
  EXPECT_EQ(c.index(700.0), 1.67);
  EXPECT_TRUE(std::isinf(c.abbeNumber()));
  EXPECT_EQ(Glass::air().index(500.0), 1.0);
  EXPECT_EQ(Glass::constant(1.0).model(), GlassModel::kAir);
}

}  // namespace glass_test
}  // namespace camsim
