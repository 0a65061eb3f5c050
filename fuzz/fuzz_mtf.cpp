// libFuzzer harness: the slanted-edge MTF (sensor/measure/slanted_edge.h) on arbitrary
// input: the ROI text `camsim mtf --roi` parses (parseEdgeRoi), then measureSfr on a small
// image built from the bytes. Input layout: the ROI text up to the first newline; then one
// byte for the fit order (1 or 2, by parity) and the orientation (auto, vertical,
// horizontal), two bytes for the width and height (8 … 71 px), and the pixels, one byte
// each (value/255; a byte 255 stands for NaN or ∞ every 17th pixel), repeated to fill.
// Bad input must end in InputError; a result must hold only finite numbers, MTF(0) = 1,
// frequencies rising from 0 to 1 cycle/px.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "fuzz/fuzz_check.h"
#include "sensor/base/input_error.h"
#include "sensor/measure/slanted_edge.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::size_t pos = 0;
  std::string roiText;
  while (pos < size && data[pos] != '\n') roiText += static_cast<char>(data[pos++]);
  ++pos;
  camsim::EdgeRoi roi;
  try {
    roi = camsim::parseEdgeRoi(roiText);
  } catch (const camsim::InputError&) {
    return 0;
  }
  if (pos + 3 > size) return 0;
  camsim::SfrOptions options;
  options.fitOrder = 1 + data[pos] % 2;
  options.orientation = static_cast<camsim::EdgeOrientation>((data[pos] / 2) % 3);
  const int width = 8 + data[pos + 1] % 64, height = 8 + data[pos + 2] % 64;
  pos += 3;
  camsim::Image image(width, height, {"Y"});
  const std::size_t n = size - pos;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const std::uint8_t b = n > 0 ? data[pos + i % n] : 0;
    image.pixels[i] = b == 255 && i % 17 == 0 ? std::numeric_limits<float>::quiet_NaN()
                                              : static_cast<float>(b) / 255.0f;
  }
  try {
    const camsim::SfrResult r = camsim::measureSfr(image, roi, options);
    FUZZ_CHECK(!r.mtf.empty() && r.mtf.size() == r.frequency.size());
    FUZZ_CHECK(r.mtf[0] == 1.0 && r.frequency.front() == 0.0 && r.frequency.back() == 1.0);
    for (std::size_t k = 0; k < r.mtf.size(); ++k) {
      FUZZ_CHECK(std::isfinite(r.mtf[k]) && r.mtf[k] >= 0.0);
      if (k > 0) FUZZ_CHECK(r.frequency[k] > r.frequency[k - 1]);
    }
    FUZZ_CHECK(std::isfinite(r.angleDeg) && r.angleDeg >= 1.0 && r.angleDeg <= 40.0);
    FUZZ_CHECK(std::isfinite(r.mtfAtNyquist) && std::isfinite(r.edgeX) && std::isfinite(r.edgeY));
    FUZZ_CHECK(!r.mtf50 || (std::isfinite(*r.mtf50) && *r.mtf50 > 0.0 && *r.mtf50 <= 1.0));
    FUZZ_CHECK(r.rowsUsed >= 1 && r.emptyBins >= 0);
  } catch (const camsim::InputError&) {
  }
  return 0;
}
