#include "integrator/lights/rgb_emission_table.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "integrator/textures/reflectance_uplift.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

constexpr int kN = RgbEmissionTable::kNodes;
constexpr int kOthers[3][2] = {{1, 2}, {0, 2}, {0, 1}};

// The node's reflectance: ½ in `channel`, the other two at ia, ib of kN − 1 steps over [0, ½].
glm::dvec3 nodeReflectance(int channel, int ia, int ib) {
  glm::dvec3 rho(0.0);
  rho[channel] = 0.5;
  rho[kOthers[channel][0]] = 0.5 * ia / (kN - 1);
  rho[kOthers[channel][1]] = 0.5 * ib / (kN - 1);
  return rho;
}

size_t nodeIndex(int channel, int ia, int ib) {
  return (static_cast<size_t>(channel) * kN + static_cast<size_t>(ia)) * kN +
         static_cast<size_t>(ib);
}

}  // namespace

RgbEmissionTable::RgbEmissionTable() : nodes_(3 * kN * kN, glm::dvec3(0.0)) {
  const ReflectanceUplift& uplift = ReflectanceUplift::linearRec709();
  tbb::parallel_for(0, 3 * kN, [&](int row) {
    const int channel = row / kN, ia = row % kN;
    for (int ib = 0; ib < kN; ++ib) {
      const SigmoidPolynomial p = uplift.fit(nodeReflectance(channel, ia, ib));
      nodes_[nodeIndex(channel, ia, ib)] = glm::dvec3(p.c0, p.c1, p.c2);
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
