// Dark frames as the noise source: recorded (or simulated) frames taken with the lens
// capped supply every signal-independent term at once — black level and its per-channel
// offsets, read noise of any shape, temporal and fixed row/column noise, DSNU, dark
// current and hot or stuck photosites — exactly as the camera produced them, instead of
// the parametric terms of sensor_noise.h.
//
// | field        | unit | meaning |
// |--------------|------|---------|
// | width,height | px   | frame size: must equal the exposed image's |
// | blackLevelDn | DN   | the frames' black level: must equal the sensor's |
// | frames       | DN   | row-major 16-bit values, black level included |
// | names        | —    | where each frame came from (for messages and the sidecar) |
//
// With dark frames, expose() in noise mode full computes, per photosite,
//   DN = clamp(round(K · min(Poisson(μ_e) · (1 + σ_prnu·a(x, y)), full well) + d_j(x, y)), 0, white)
// where j = streamKey(noise seed, frame) mod (number of frames): each output frame adds
// one whole dark frame, chosen by (seed, frame), so the injected noise has the source
// frames' per-pixel mean and variance and their row and column structure. The exposure
// time, temperature and ISO of the dark frames are the user's to match.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace camsim {

struct DarkFrameSet {
  int width = 0, height = 0;
  double blackLevelDn = 0.0;
  std::vector<std::vector<std::uint16_t>> frames;
  std::vector<std::string> names;

  // The frame an output (noise seed, frame) uses.
  std::size_t frameFor(std::uint64_t noiseSeed, std::uint64_t frame) const;
};

}  // namespace camsim
