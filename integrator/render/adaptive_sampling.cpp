#include "integrator/render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

#include "sensor/base/check.h"

namespace camsim {

int adaptiveMinSppFor(int spp, int minSppSetting) {
  if (minSppSetting > 0) return minSppSetting;
  const int root = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(spp))));
  const int m = std::max(4, root);
  return m + (m & 1);
}

AdaptiveState::AdaptiveState(AdaptiveSampling settings, glm::ivec2 resolution)
    : settings_(settings),
      width_(resolution.x),
      active_(static_cast<std::size_t>(resolution.x) * static_cast<std::size_t>(resolution.y), 1) {
  CAMSIM_CHECK(settings.threshold > 0.0 && settings.minSpp >= 2 && settings.minSpp % 2 == 0);
}

bool AdaptiveState::check(const Film& film, glm::ivec2 lo, glm::ivec2 hi) {
  if (!(imageMean_ > 0.0)) return true;  // black so far: no scale to judge by; keep going
  constexpr int kSide = 16;              // kRenderTileSize (render.h)
  const glm::ivec2 size = hi - lo;
  CAMSIM_CHECK(size.x > 0 && size.y > 0 && size.x <= kSide && size.y <= kSide);
  // Which of the tile's active pixels are not converged (e_p ≥ T).
  bool noisy[kSide][kSide] = {};
  const double eps = 0.01 * imageMean_;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      const glm::ivec2 p = lo + glm::ivec2(x, y);
      if (!active(p)) continue;
      const double value = film.errorValue(p);
      const double e =
          std::abs(value - film.errorOddMean(p)) / std::sqrt(imageMean_ * (std::abs(value) + eps));
      // A NaN score (the film rejects non-finite samples, so only from overflow) keeps it on.
      noisy[y][x] = !(e < settings_.threshold);
    }
  // Dilation: an active pixel stays active if any of its 3 × 3 neighbours in the tile is
  // noisy. Inactive pixels were not scored (noisy = false), so nothing restarts.
  bool any = false;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      const glm::ivec2 p = lo + glm::ivec2(x, y);
      if (!active(p)) continue;
      bool keep = false;
      for (int j = std::max(y - 1, 0); j <= std::min(y + 1, size.y - 1) && !keep; ++j)
        for (int i = std::max(x - 1, 0); i <= std::min(x + 1, size.x - 1) && !keep; ++i)
          keep = noisy[j][i];
      active_[index(p)] = keep ? 1 : 0;
      any = any || keep;
    }
  return any;
}

bool AdaptiveState::anyActive() const {
  return std::any_of(active_.begin(), active_.end(), [](std::uint8_t a) { return a != 0; });
}

}  // namespace camsim
