#include "integrator/rgb_emission_table.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "sensor/check.h"
#include "sensor/cie.h"
#include "sensor/color_space.h"
#include "sensor/spectrum.h"

namespace camsim {
namespace {

constexpr int kN = RgbEmissionTable::kNodes;
constexpr int kOthers[3][2] = {{1, 2}, {0, 2}, {0, 1}};

double sigmoid(double x) {
  return 0.5 + x / (2.0 * std::sqrt(1.0 + x * x));
}

// Colour-matching weights per wavelength bin under D65, normalised to Y(1) = 1.
struct FitBins {
  std::vector<double> t;
  std::vector<glm::dvec3> xyz;
};

const FitBins& fitBins() {
  static const FitBins bins = [] {
    const Spectrum& d65 = RgbColorSpace::linearRec709().illuminant();
    const Cie1931& cie = Cie1931::get();
    const double norm = innerProduct(d65, cie.y);
    FitBins b;
    for (int start = 0; start < kSpectrumSamples; start += RgbEmissionTable::kBinNm) {
      const int end = std::min(start + RgbEmissionTable::kBinNm, kSpectrumSamples);
      glm::dvec3 w(0.0);
      for (int i = start; i < end; ++i)
        w += static_cast<double>(d65.sample(i)) *
             glm::dvec3(cie.x.sample(i), cie.y.sample(i), cie.z.sample(i));
      b.t.push_back(0.5 * (start + end - 1) / (kLambdaMaxNm - kLambdaMinNm));
      b.xyz.push_back(w / norm);
    }
    return b;
  }();
  return bins;
}

// Colour of the coefficients c and its Jacobian (column k = ∂XYZ/∂c_k).
glm::dvec3 colourOf(const glm::dvec3& c, glm::dmat3* jacobian) {
  const FitBins& b = fitBins();
  glm::dvec3 xyz(0.0);
  glm::dmat3 j(0.0);
  for (size_t i = 0; i < b.t.size(); ++i) {
    const double t = b.t[i];
    const double x = (c[0] * t + c[1]) * t + c[2];
    xyz += sigmoid(x) * b.xyz[i];
    if (jacobian) {
      const double ds = 0.5 / std::pow(1.0 + x * x, 1.5);
      j[0] += ds * t * t * b.xyz[i];
      j[1] += ds * t * b.xyz[i];
      j[2] += ds * b.xyz[i];
    }
  }
  if (jacobian) *jacobian = j;
  return xyz;
}

// Levenberg–Marquardt from c towards the colour target.
glm::dvec3 refine(glm::dvec3 c, const glm::dvec3& target) {
  double damping = 1e-3;
  glm::dmat3 j;
  glm::dvec3 r = colourOf(c, &j) - target;
  double err = glm::dot(r, r);
  for (int iter = 0; iter < 60 && err > 1e-16; ++iter) {
    const glm::dmat3 jtj = glm::transpose(j) * j;
    const glm::dvec3 jtr = glm::transpose(j) * r;
    bool improved = false;
    for (int tries = 0; tries < 12 && !improved; ++tries) {
      glm::dmat3 a = jtj;
      for (int k = 0; k < 3; ++k) a[k][k] += damping * (jtj[k][k] + 1e-12);
      const glm::dvec3 next = c - glm::inverse(a) * jtr;
      glm::dmat3 jn;
      const glm::dvec3 rn = colourOf(next, &jn) - target;
      const double en = glm::dot(rn, rn);
      if (std::isfinite(en) && en < err) {
        c = next;
        r = rn;
        j = jn;
        err = en;
        damping = std::max(damping * 0.3, 1e-9);
        improved = true;
      } else {
        damping *= 10.0;
      }
    }
    if (!improved) break;
  }
  return c;
}

glm::dvec3 nodeColour(int channel, int ia, int ib) {
  glm::dvec3 rho(0.0);
  rho[channel] = 0.5;
  rho[kOthers[channel][0]] = 0.5 * ia / (kN - 1);
  rho[kOthers[channel][1]] = 0.5 * ib / (kN - 1);
  return RgbColorSpace::linearRec709().toXyz(rho);
}

size_t nodeIndex(int channel, int ia, int ib) {
  return (static_cast<size_t>(channel) * kN + static_cast<size_t>(ia)) * kN +
         static_cast<size_t>(ib);
}

}  // namespace

glm::dvec3 RgbEmissionTable::reflectanceXyz(const glm::dvec3& coefficients) {
  return colourOf(coefficients, nullptr);
}

RgbEmissionTable::RgbEmissionTable() : nodes_(3 * kN * kN, glm::dvec3(0.0)) {
  // Walk from grey (ia = ib = kN − 1: ρ = (½, ½, ½), c = 0 exactly) towards saturation:
  // each node starts from its fitted neighbour and approaches its colour in 4 steps.
  constexpr int kSteps = 4;
  tbb::parallel_for(0, 3, [&](int channel) {
    for (int ia = kN - 1; ia >= 0; --ia)
      for (int ib = kN - 1; ib >= 0; --ib) {
        if (ia == kN - 1 && ib == kN - 1) continue;
        const bool fromRow = ib < kN - 1;
        const int na = fromRow ? ia : ia + 1, nb = fromRow ? ib + 1 : ib;
        glm::dvec3 c = nodes_[nodeIndex(channel, na, nb)];
        const glm::dvec3 from = nodeColour(channel, na, nb), to = nodeColour(channel, ia, ib);
        for (int s = 1; s <= kSteps; ++s)
          c = refine(c, from + (to - from) * (static_cast<double>(s) / kSteps));
        nodes_[nodeIndex(channel, ia, ib)] = c;
      }
  });
}

const RgbEmissionTable& RgbEmissionTable::get() {
  static const RgbEmissionTable table;
  return table;
}

SigmoidCoefficients RgbEmissionTable::lookup(const glm::dvec3& rgb) const {
  const double m = std::max({rgb.x, rgb.y, rgb.z});
  CAMSIM_CHECK(m > 0.0 && rgb.x >= 0.0 && rgb.y >= 0.0 && rgb.z >= 0.0);
  const int channel = rgb.x == m ? 0 : (rgb.y == m ? 1 : 2);
  int i[2];
  double f[2];
  for (int k = 0; k < 2; ++k) {
    const double x = std::clamp(rgb[kOthers[channel][k]] / m * (kN - 1), 0.0, double{kN - 1});
    i[k] = std::min(static_cast<int>(x), kN - 2);
    f[k] = x - i[k];
  }
  glm::dvec3 c(0.0);
  for (int da = 0; da < 2; ++da)
    for (int db = 0; db < 2; ++db)
      c += (da ? f[0] : 1.0 - f[0]) * (db ? f[1] : 1.0 - f[1]) *
           nodes_[nodeIndex(channel, i[0] + da, i[1] + db)];
  return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

}  // namespace camsim
