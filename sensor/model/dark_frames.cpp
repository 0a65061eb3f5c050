#include "sensor/model/dark_frames.h"

#include "sensor/base/check.h"
#include "sensor/base/counter_rng.h"

namespace camsim {

std::size_t DarkFrameSet::frameFor(std::uint64_t noiseSeed, std::uint64_t frame) const {
  CAMSIM_CHECK(!frames.empty());
  constexpr std::uint64_t kDarkFrameDomain = 0x6461726b66ull;  // "darkf"
  return static_cast<std::size_t>(streamKey(kDarkFrameDomain, noiseSeed, frame) %
                                  static_cast<std::uint64_t>(frames.size()));
}

}  // namespace camsim
