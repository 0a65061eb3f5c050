#include "sensor/isp/color_difference.h"

#include <cmath>
#include <numbers>
#include <string>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

constexpr double kDelta = 6.0 / 29.0;
constexpr double kDegree = std::numbers::pi / 180.0;

double labF(double t) {
  if (t > kDelta * kDelta * kDelta) return std::cbrt(t);
  return t / (3.0 * kDelta * kDelta) + 4.0 / 29.0;
}

// Hue angle in degrees, [0, 360); 0 for the achromatic (0, 0).
double hueDegrees(double b, double a) {
  if (a == 0.0 && b == 0.0) return 0.0;
  double h = std::atan2(b, a) / kDegree;
  if (h < 0.0) h += 360.0;
  return h;
}

double pow7(double x) {
  const double x2 = x * x;
  return x2 * x2 * x2 * x;
}

}  // namespace

glm::dvec3 xyzToLab(const glm::dvec3& xyz, const glm::dvec3& white) {
  const double fx = labF(xyz.x / white.x);
  const double fy = labF(xyz.y / white.y);
  const double fz = labF(xyz.z / white.z);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double deltaE2000(const glm::dvec3& lab1, const glm::dvec3& lab2, const Ciede2000Weights& k) {
  const double pow25_7 = pow7(25.0);
  // Step 1: a′, C′, h′.
  const double c1 = std::hypot(lab1.y, lab1.z);
  const double c2 = std::hypot(lab2.y, lab2.z);
  const double cMean7 = pow7(0.5 * (c1 + c2));
  const double g = 0.5 * (1.0 - std::sqrt(cMean7 / (cMean7 + pow25_7)));
  const double a1 = (1.0 + g) * lab1.y;
  const double a2 = (1.0 + g) * lab2.y;
  const double cp1 = std::hypot(a1, lab1.z);
  const double cp2 = std::hypot(a2, lab2.z);
  const double h1 = hueDegrees(lab1.z, a1);
  const double h2 = hueDegrees(lab2.z, a2);

  // Step 2: ΔL′, ΔC′, ΔH′.
  const double dL = lab2.x - lab1.x;
  const double dC = cp2 - cp1;
  const double cProduct = cp1 * cp2;
  double dh = 0.0;
  if (cProduct != 0.0) {
    dh = h2 - h1;
    if (dh > 180.0)
      dh -= 360.0;
    else if (dh < -180.0)
      dh += 360.0;
  }
  const double dH = 2.0 * std::sqrt(cProduct) * std::sin(0.5 * dh * kDegree);

  // Step 3: weighting functions and the rotation term.
  const double lMean = 0.5 * (lab1.x + lab2.x);
  const double cMean = 0.5 * (cp1 + cp2);
  double hMean = h1 + h2;
  if (cProduct != 0.0) {
    if (std::abs(h1 - h2) <= 180.0)
      hMean = 0.5 * (h1 + h2);
    else if (h1 + h2 < 360.0)
      hMean = 0.5 * (h1 + h2 + 360.0);
    else
      hMean = 0.5 * (h1 + h2 - 360.0);
  }
  const double t = 1.0 - 0.17 * std::cos((hMean - 30.0) * kDegree) +
                   0.24 * std::cos(2.0 * hMean * kDegree) +
                   0.32 * std::cos((3.0 * hMean + 6.0) * kDegree) -
                   0.20 * std::cos((4.0 * hMean - 63.0) * kDegree);
  const double dTheta = 30.0 * std::exp(-std::pow((hMean - 275.0) / 25.0, 2.0));
  const double cMeanP7 = pow7(cMean);
  const double rC = 2.0 * std::sqrt(cMeanP7 / (cMeanP7 + pow25_7));
  const double l50 = (lMean - 50.0) * (lMean - 50.0);
  const double sL = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double sC = 1.0 + 0.045 * cMean;
  const double sH = 1.0 + 0.015 * cMean * t;
  const double rT = -std::sin(2.0 * dTheta * kDegree) * rC;

  const double termL = dL / (k.kL * sL);
  const double termC = dC / (k.kC * sC);
  const double termH = dH / (k.kH * sH);
  return std::sqrt(termL * termL + termC * termC + termH * termH + rT * termC * termH);
}

Image xyzToLab(const Image& xyz, const glm::dvec3& white) {
  if (xyz.channelCount() != 3)
    throw InputError(
        {}, "", "xyzToLab needs 3 channels (X, Y, Z), got " + std::to_string(xyz.channelCount()));
  Image lab(xyz.width, xyz.height, {"L", "a", "b"});
  for (size_t i = 0; i < xyz.pixels.size(); i += 3) {
    const glm::dvec3 v =
        xyzToLab(glm::dvec3(xyz.pixels[i], xyz.pixels[i + 1], xyz.pixels[i + 2]), white);
    for (int c = 0; c < 3; ++c) lab.pixels[i + static_cast<size_t>(c)] = static_cast<float>(v[c]);
  }
  return lab;
}

Image deltaE2000(const Image& lab1, const Image& lab2, const Ciede2000Weights& k) {
  if (lab1.channelCount() != 3 || lab2.channelCount() != 3 || lab1.width != lab2.width ||
      lab1.height != lab2.height)
    throw InputError({}, "", "deltaE2000 needs two 3-channel Lab images of the same size");
  Image out(lab1.width, lab1.height, {"dE00"});
  for (size_t p = 0; p < out.pixels.size(); ++p) {
    const size_t i = 3 * p;
    const glm::dvec3 a(lab1.pixels[i], lab1.pixels[i + 1], lab1.pixels[i + 2]);
    const glm::dvec3 b(lab2.pixels[i], lab2.pixels[i + 1], lab2.pixels[i + 2]);
    out.pixels[p] = static_cast<float>(deltaE2000(a, b, k));
  }
  return out;
}

}  // namespace camsim
