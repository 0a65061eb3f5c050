#include "sensor/isp/color_correction.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/matrix.hpp>

#include "sensor/base/input_error.h"
#include "sensor/isp/color_difference.h"
#include "sensor/isp/white_balance.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

glm::dvec3 toVec3(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

glm::dmat3 gramian(const std::vector<glm::dvec3>& from) {
  glm::dmat3 a(0.0);
  for (const glm::dvec3& f : from) a += glm::outerProduct(f, f);
  if (!(std::abs(glm::determinant(a)) > 0.0))
    throw InputError({}, "", "colour fit: the samples do not span three dimensions");
  return a;
}

}  // namespace

ChartSamples colorCheckerSamples(const std::vector<Spectrum>& qe, const Spectrum& illuminant,
                                 const std::filesystem::path& colorCheckerCsv) {
  if (qe.size() != 3)
    throw InputError({}, "qe",
                     "a colour fit needs 3 QE curves (R, G, B), got " + std::to_string(qe.size()));
  const SpectralTable chart = readSpectralCsv(colorCheckerCsv);
  if (chart.columns.size() < 3)
    throw InputError({chart.source, 0, 0}, "", "a colour fit needs at least 3 reflectance columns");
  ChartSamples s;
  for (size_t p = 0; p < chart.columns.size(); ++p) {
    const Spectrum r = chart.spectrum(p, Extrapolation::kClamp);
    s.camera.push_back(toVec3(cameraResponse(qe, r, illuminant)));
    s.xyz.push_back(reflectanceToXyz(r, illuminant));
  }
  const Spectrum one = Spectrum::constant(1.0);
  s.cameraWhite = toVec3(cameraResponse(qe, one, illuminant));
  s.xyzWhite = reflectanceToXyz(one, illuminant);
  return s;
}

glm::dmat3 fitLinearMap(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to) {
  CAMSIM_CHECK(from.size() == to.size());
  glm::dmat3 tf(0.0);
  for (size_t i = 0; i < from.size(); ++i) tf += glm::outerProduct(to[i], from[i]);
  return tf * glm::inverse(gramian(from));
}

glm::dmat3 fitLinearMapConstrained(const std::vector<glm::dvec3>& from,
                                   const std::vector<glm::dvec3>& to, const glm::dvec3& u,
                                   const glm::dvec3& target) {
  const glm::dmat3 m0 = fitLinearMap(from, to);
  const glm::dvec3 aInvU = glm::inverse(gramian(from)) * u;
  const double denominator = glm::dot(u, aInvU);
  CAMSIM_CHECK(denominator > 0.0);
  return m0 + glm::outerProduct(target - m0 * u, aInvU) / denominator;
}

glm::dmat3 ColorCorrection::rawToXyz() const {
  glm::dmat3 gains(1.0);
  for (int i = 0; i < 3; ++i) gains[i][i] = whiteBalance[i];
  return cameraToXyz * gains;
}

ColorCorrection fitColorCorrection(const std::vector<Spectrum>& qe, const Spectrum& illuminant,
                                   const std::filesystem::path& colorCheckerCsv,
                                   const ColorCorrectionOptions& options) {
  const ChartSamples s = colorCheckerSamples(qe, illuminant, colorCheckerCsv);
  const std::vector<double> white = {s.cameraWhite.x, s.cameraWhite.y, s.cameraWhite.z};
  ColorCorrection cc;
  cc.whiteBalance = toVec3(gainsFromWhite(white, 1));  // throws unless every w_k > 0
  cc.adaptation = bradfordAdaptation(s.xyzWhite, d65WhiteXyz());
  std::vector<glm::dvec3> balanced, target;
  for (size_t p = 0; p < s.camera.size(); ++p) {
    balanced.push_back(s.camera[p] / s.cameraWhite);
    target.push_back(cc.adaptation * s.xyz[p]);
  }
  cc.cameraToXyz = options.preserveWhite
                       ? fitLinearMapConstrained(balanced, target, glm::dvec3(1.0), d65WhiteXyz())
                       : fitLinearMap(balanced, target);
  CAMSIM_CHECK(options.workingSpace != nullptr);
  cc.xyzToWorking = xyzD65ToWorkingSpace(*options.workingSpace);
  cc.workingSpace = options.workingSpace->name();
  return cc;
}

ChartError colorCheckerError(const ColorCorrection& cc, const std::vector<Spectrum>& qe,
                             const Spectrum& illuminant,
                             const std::filesystem::path& colorCheckerCsv) {
  const ChartSamples s = colorCheckerSamples(qe, illuminant, colorCheckerCsv);
  const glm::dvec3 white = d65WhiteXyz();
  const glm::dmat3 adaptation = bradfordAdaptation(s.xyzWhite, white);
  ChartError e;
  for (size_t p = 0; p < s.camera.size(); ++p) {
    const glm::dvec3 estimate = cc.cameraToXyz * (s.camera[p] / s.cameraWhite);
    const double de = deltaE2000(xyzToLab(adaptation * s.xyz[p], white), xyzToLab(estimate, white));
    e.deltaE.push_back(de);
    e.mean += de / static_cast<double>(s.camera.size());
    e.max = std::max(e.max, de);
  }
  return e;
}

Image applyColorMatrix(const Image& image, const glm::dmat3& m,
                       const std::vector<std::string>& outputChannels) {
  if (image.channelCount() != 3 || outputChannels.size() != 3)
    throw InputError({}, "",
                     "a colour matrix needs 3 input and 3 output channels, got " +
                         std::to_string(image.channelCount()) + " and " +
                         std::to_string(outputChannels.size()));
  Image out(image.width, image.height, outputChannels);
  for (size_t i = 0; i < image.pixels.size(); i += 3) {
    const glm::dvec3 v = m * glm::dvec3(image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]);
    for (int c = 0; c < 3; ++c) out.pixels[i + static_cast<size_t>(c)] = static_cast<float>(v[c]);
  }
  return out;
}

}  // namespace camsim
