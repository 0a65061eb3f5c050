// Tests for sensor/demosaic: a synthetic zone plate and a slanted edge, sampled on each
// Bayer layout and demosaicked by both methods (PSNR printed; Malvar–He–Cutler must beat
// bilinear by ≥ 3 dB on the zone plate), constant and linear images reproduced, layouts,
// mirrored borders and the non-Bayer cases.
#include "sensor/isp/demosaic.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <glm/vec3.hpp>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

const char* const kLayouts[] = {"RGGB", "BGGR", "GRBG", "GBRG"};

Image rgbImage(int w, int h, const std::function<glm::dvec3(double, double)>& f) {
  Image img(w, h, {"R", "G", "B"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::dvec3 v = f(x, y);
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<float>(v[c]);
    }
  return img;
}

// Each photosite keeps its own CFA channel of the full image.
Image mosaicOf(const Image& rgb, const CfaLayout& cfa) {
  Image m(rgb.width, rgb.height, {"CFA"});
  for (int y = 0; y < rgb.height; ++y)
    for (int x = 0; x < rgb.width; ++x) m.at(x, y, 0) = rgb.at(x, y, cfa.channelAt(x, y));
  return m;
}

// PSNR over all pixels and channels, peak 1.
double psnr(const Image& a, const Image& b) {
  double se = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]);
    se += d * d;
  }
  return 10.0 * std::log10(static_cast<double>(a.pixels.size()) / se);
}

// Zone plate cos(2π f_e r²/W): the local frequency grows linearly with the radius r, from
// 0 at the centre to f_e cycles/pixel at the edge midpoints (f_e·√2 in the corners).
// f_e = 0.25, the Nyquist frequency of the R and B photosites, is the main test chart;
// f_e = 0.5 (up to the full-grid Nyquist, aliased for every method) is reported too.
// Slightly different amplitudes per channel: a real, correlated colour image.
Image zonePlate(int size, double edgeFrequency) {
  const double c = 0.5 * (size - 1);
  return rgbImage(size, size, [&](double x, double y) {
    const double r2 = (x - c) * (x - c) + (y - c) * (y - c);
    const double v = std::cos(2.0 * std::numbers::pi * edgeFrequency * r2 / size);
    return glm::dvec3(0.5 + 0.40 * v, 0.5 + 0.45 * v, 0.45 + 0.35 * v);
  });
}

// An edge 5° off vertical between two colours, area-sampled (8 × 8 sub-samples per pixel).
Image slantedEdge(int size) {
  const double slope = std::tan(5.0 * std::numbers::pi / 180.0);
  const glm::dvec3 dark(0.15, 0.20, 0.25), light(0.80, 0.70, 0.60);
  return rgbImage(size, size, [&](double x, double y) {
    int inside = 0;
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const double sx = x + (i + 0.5) / 8.0, sy = y + (j + 0.5) / 8.0;
        inside += sx > 0.5 * size + slope * (sy - 0.5 * size) ? 1 : 0;
      }
    const double t = inside / 64.0;
    return dark * (1.0 - t) + light * t;
  });
}

struct Psnr {
  double bilinear, mhc;
};

Psnr psnrBoth(const Image& truth, const CfaLayout& cfa) {
  const Image m = mosaicOf(truth, cfa);
  return {psnr(demosaic(m, cfa, DemosaicMethod::kBilinear), truth),
          psnr(demosaic(m, cfa, DemosaicMethod::kMalvarHeCutler), truth)};
}

TEST(Demosaic, ZonePlateAndSlantedEdgePsnrOnEveryLayout) {
  // 256 × 256, PSNR over every pixel (borders included) and channel.
  const Image zone = zonePlate(256, 0.25), fullBand = zonePlate(256, 0.5);
  const Image edge = slantedEdge(256);
  for (const char* name : kLayouts) {
    const CfaLayout cfa = CfaLayout::fromName(name);
    const Psnr z = psnrBoth(zone, cfa), f = psnrBoth(fullBand, cfa), e = psnrBoth(edge, cfa);
    std::printf(
        "[ %s ] bilinear / MHC: zone plate %.2f / %.2f dB, full-band zone plate "
        "%.2f / %.2f dB, slanted edge %.2f / %.2f dB\n",
        name, z.bilinear, z.mhc, f.bilinear, f.mhc, e.bilinear, e.mhc);
    EXPECT_GE(z.mhc - z.bilinear, 3.0) << name;  // measured +9.0 dB
    EXPECT_GT(f.mhc, f.bilinear) << name;        // measured +3.3 dB
    EXPECT_GT(e.mhc, e.bilinear) << name;        // measured +3.6 dB
  }
}

TEST(Demosaic, ConstantImageStaysConstant) {
  // Odd size: the mirrored border covers every tile phase. Tolerance 1e-6 (float sums).
  const Image flat = rgbImage(9, 7, [](double, double) { return glm::dvec3(0.2, 0.5, 0.8); });
  for (const char* name : kLayouts) {
    const CfaLayout cfa = CfaLayout::fromName(name);
    for (const DemosaicMethod m : {DemosaicMethod::kBilinear, DemosaicMethod::kMalvarHeCutler}) {
      const Image out = demosaic(mosaicOf(flat, cfa), cfa, m);
      ASSERT_EQ(out.channels, (std::vector<std::string>{"R", "G", "B"}));
      for (size_t i = 0; i < out.pixels.size(); ++i)
        ASSERT_NEAR(out.pixels[i], flat.pixels[i], 1e-6) << name << " pixel " << i / 3;
    }
  }
}

TEST(Demosaic, LinearRampIsExactInTheInteriorOnEveryLayout) {
  // Both kernels are exact for a linear image (bilinear averages of symmetric pairs; the
  // MHC correction is a Laplacian, zero on a plane), so a wrong channel or kernel choice
  // for any layout would show. Border pixels (mirrored) are excluded; tolerance 1e-5.
  const Image ramp = rgbImage(12, 10, [](double x, double y) {
    return glm::dvec3(0.01 * x + 0.02 * y, 0.5 - 0.015 * x + 0.01 * y, 0.1 + 0.03 * x - 0.02 * y);
  });
  for (const char* name : kLayouts) {
    const CfaLayout cfa = CfaLayout::fromName(name);
    for (const DemosaicMethod m : {DemosaicMethod::kBilinear, DemosaicMethod::kMalvarHeCutler}) {
      const Image out = demosaic(mosaicOf(ramp, cfa), cfa, m);
      for (int y = 2; y < 8; ++y)
        for (int x = 2; x < 10; ++x)
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(out.at(x, y, c), ramp.at(x, y, c), 1e-5) << name << " " << x << "," << y;
    }
  }
}

TEST(Demosaic, KnownSamplesPassThroughAndBordersMirror) {
  const Image zone = zonePlate(16, 0.25);
  for (const char* name : kLayouts) {
    const CfaLayout cfa = CfaLayout::fromName(name);
    const Image m = mosaicOf(zone, cfa);
    const Image out = demosaic(m, cfa, DemosaicMethod::kMalvarHeCutler);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) ASSERT_EQ(out.at(x, y, cfa.channelAt(x, y)), m.at(x, y, 0));
    // Bilinear G at the top-left corner of a layout with R/B there: the mirrored
    // neighbours (x = −1 → 1, y = −1 → 1) count twice: (2·m(1,0) + 2·m(0,1)) / 4.
    if (cfa.channelAt(0, 0) != 1) {
      const Image b = demosaic(m, cfa, DemosaicMethod::kBilinear);
      EXPECT_FLOAT_EQ(b.at(0, 0, 1), 0.5f * (m.at(1, 0, 0) + m.at(0, 1, 0))) << name;
    }
  }
}

TEST(Demosaic, MonochromeAndStackedSkipNonBayerThrows) {
  Image mono(3, 2, {"Y"});
  mono.pixels = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
  EXPECT_EQ(demosaic(mono, CfaLayout::fromName("mono"), DemosaicMethod::kMalvarHeCutler).pixels,
            mono.pixels);
  Image xyz(1, 1, {"X", "Y", "Z"});
  xyz.pixels = {0.3f, 0.4f, 0.5f};
  const Image stacked = demosaic(xyz, CfaLayout::fromName("xyz"), DemosaicMethod::kBilinear);
  EXPECT_EQ(stacked.channels, xyz.channels);
  EXPECT_EQ(stacked.pixels, xyz.pixels);

  CfaLayout rgbw{2, 2, {0, 1, 3, 2}, {"R", "G", "B", "W"}, "RGBW"};
  EXPECT_FALSE(isBayer(rgbw));
  EXPECT_THROW(demosaic(Image(4, 4, {"CFA"}), rgbw, DemosaicMethod::kBilinear), InputError);
  CfaLayout rows{2, 2, {0, 2, 1, 1}, {"R", "G", "B"}, "RBGG"};  // G not on a diagonal
  EXPECT_FALSE(isBayer(rows));
  for (const char* name : kLayouts) EXPECT_TRUE(isBayer(CfaLayout::fromName(name))) << name;
  EXPECT_THROW(demosaic(Image(4, 4, {"R", "G", "B"}), CfaLayout::fromName("RGGB"),
                        DemosaicMethod::kBilinear),
               InputError);
}

}  // namespace
}  // namespace camsim
