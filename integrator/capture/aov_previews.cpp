#include "integrator/capture/aov_previews.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "sensor/spectra/color_space.h"

namespace camsim {
namespace {

std::uint8_t byte(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5)];
}

// HSV (h in [0, 1)) to RGB.
std::array<double, 3> hsv(double h, double s, double v) {
  const double i = std::floor(h * 6.0), f = h * 6.0 - i;
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (static_cast<int>(i) % 6) {
    case 0:
      return {v, t, p};
    case 1:
      return {q, v, p};
    case 2:
      return {p, v, t};
    case 3:
      return {p, q, v};
    case 4:
      return {t, p, v};
    default:
      return {v, p, q};
  }
}

}  // namespace

std::vector<AovPreview> aovPreviews(const Image& a) {
  std::vector<AovPreview> out;
  const std::size_t n = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
  auto make = [&](const std::string& suffix) -> AovPreview& {
    AovPreview& p = out.emplace_back();
    p.suffix = suffix;
    p.width = a.width;
    p.height = a.height;
    p.rgb.assign(n * 3, 0);
    return p;
  };
  auto value = [&](std::size_t px, int c) {
    return static_cast<double>(a.pixels[px * a.channels.size() + static_cast<std::size_t>(c)]);
  };
  const int cov = a.channelIndex("coverage.A");
  if (const int z = a.channelIndex("depth.Z"); z >= 0) {
    std::vector<double> logs;
    for (std::size_t px = 0; px < n; ++px)
      if (value(px, cov) > 0.0 && value(px, z) > 0.0) logs.push_back(std::log(value(px, z)));
    const double lo = percentile(logs, 0.01), hi = percentile(logs, 0.99);
    AovPreview& p = make("depth");
    for (std::size_t px = 0; px < n; ++px) {
      if (!(value(px, cov) > 0.0 && value(px, z) > 0.0)) continue;
      const double f = hi > lo ? (std::log(value(px, z)) - lo) / (hi - lo) : 0.0;
      std::fill_n(&p.rgb[px * 3], 3, byte(1.0 - 0.85 * std::clamp(f, 0.0, 1.0)));
    }
  }
  if (const int nx = a.channelIndex("N.X"); nx >= 0) {
    AovPreview& p = make("normal");
    for (std::size_t px = 0; px < n; ++px)
      for (int c = 0; c < 3; ++c)
        p.rgb[px * 3 + static_cast<std::size_t>(c)] =
            value(px, cov) > 0.0 ? byte(0.5 * (value(px, nx + c) + 1.0)) : 0;
  }
  if (const int r = a.channelIndex("albedo.R"); r >= 0) {
    AovPreview& p = make("albedo");
    p.srgb = true;
    for (std::size_t px = 0; px < n; ++px)
      for (int c = 0; c < 3; ++c)
        p.rgb[px * 3 + static_cast<std::size_t>(c)] =
            byte(srgbEncode(std::clamp(value(px, r + c), 0.0, 1.0)));
  }
  for (const char* kind : {"instance", "class", "material"}) {
    const int id = a.channelIndex(std::string(kind) + ".id");
    if (id < 0) continue;
    AovPreview& p = make(kind);
    for (std::size_t px = 0; px < n; ++px) {
      const auto v = static_cast<std::uint32_t>(value(px, id));
      if (v == 0) continue;
      // Golden-ratio hues: neighbouring ids get distant colours.
      const std::array<double, 3> rgb = hsv(std::fmod(v * 0.618033988749895, 1.0), 0.75, 0.95);
      for (int c = 0; c < 3; ++c)
        p.rgb[px * 3 + static_cast<std::size_t>(c)] = byte(rgb[static_cast<std::size_t>(c)]);
    }
  }
  if (const int mx = a.channelIndex("motion_fw.X"); mx >= 0) {
    std::vector<double> lengths;
    for (std::size_t px = 0; px < n; ++px)
      lengths.push_back(std::hypot(value(px, mx), value(px, mx + 1)));
    const double scale = std::max(percentile(lengths, 0.99), 1e-6);
    AovPreview& p = make("motion");
    for (std::size_t px = 0; px < n; ++px) {
      const double dx = value(px, mx), dy = value(px, mx + 1);
      const double h = std::atan2(-dy, dx) / (2.0 * M_PI) + 0.5;
      const std::array<double, 3> rgb = hsv(h, std::min(1.0, std::hypot(dx, dy) / scale), 1.0);
      for (int c = 0; c < 3; ++c)
        p.rgb[px * 3 + static_cast<std::size_t>(c)] = byte(rgb[static_cast<std::size_t>(c)]);
    }
  }
  // The masks (mask_film.h): each labelled shape's pixels (coverage ≥ ½) in its instance
  // colour, averaged where several overlap; amodal and visible side by side in two files.
  for (const char* kind : {"amodal", "visible"}) {
    const std::string prefix = std::string(kind) + "_";
    std::vector<std::pair<int, std::array<double, 3>>> masks;  // channel, colour
    for (int c = 0; c < a.channelCount(); ++c) {
      const std::string& name = a.channels[static_cast<std::size_t>(c)];
      if (name.rfind(prefix, 0) != 0) continue;
      const auto v = static_cast<std::uint32_t>(std::stoul(name.substr(prefix.size())));
      masks.emplace_back(c, hsv(std::fmod(v * 0.618033988749895, 1.0), 0.75, 0.95));
    }
    if (masks.empty()) continue;
    AovPreview& p = make(kind);
    for (std::size_t px = 0; px < n; ++px) {
      std::array<double, 3> sum{};
      int count = 0;
      for (const auto& [c, rgb] : masks) {
        if (value(px, c) < 0.5) continue;
        for (std::size_t k = 0; k < 3; ++k) sum[k] += rgb[k];
        ++count;
      }
      for (std::size_t k = 0; count > 0 && k < 3; ++k) p.rgb[px * 3 + k] = byte(sum[k] / count);
    }
  }
  if (const int v = a.channelIndex("valid.A"); v >= 0) {
    AovPreview& p = make("valid");  // white inside the camera model's image, black outside
    for (std::size_t px = 0; px < n; ++px) std::fill_n(&p.rgb[px * 3], 3, byte(value(px, v)));
  }
  return out;
}

}  // namespace camsim
