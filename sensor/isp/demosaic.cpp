#include "sensor/isp/demosaic.h"

#include <span>
#include <string>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

struct Tap {
  int dx, dy;
  float weight;
};

// Kernels as tap lists. "Row": the wanted colour lies left/right of the pixel; "column":
// above/below (the transpose).
constexpr Tap kBilinearGreen[] = {{-1, 0, 0.25f}, {1, 0, 0.25f}, {0, -1, 0.25f}, {0, 1, 0.25f}};
constexpr Tap kBilinearRow[] = {{-1, 0, 0.5f}, {1, 0, 0.5f}};
constexpr Tap kBilinearColumn[] = {{0, -1, 0.5f}, {0, 1, 0.5f}};
constexpr Tap kBilinearDiagonal[] = {
    {-1, -1, 0.25f}, {1, -1, 0.25f}, {-1, 1, 0.25f}, {1, 1, 0.25f}};

// Malvar–He–Cutler 2004, Fig. 2, weights × 1/8.
constexpr float kE = 1.0f / 8.0f;
constexpr Tap kMhcGreen[] = {{0, 0, 4 * kE},  {-1, 0, 2 * kE}, {1, 0, 2 * kE},
                             {0, -1, 2 * kE}, {0, 1, 2 * kE},  {-2, 0, -kE},
                             {2, 0, -kE},     {0, -2, -kE},    {0, 2, -kE}};
constexpr Tap kMhcRow[] = {{0, 0, 5 * kE}, {-1, 0, 4 * kE}, {1, 0, 4 * kE}, {-2, 0, -kE},
                           {2, 0, -kE},    {-1, -1, -kE},   {1, -1, -kE},   {-1, 1, -kE},
                           {1, 1, -kE},    {0, -2, kE / 2}, {0, 2, kE / 2}};
constexpr Tap kMhcColumn[] = {{0, 0, 5 * kE}, {0, -1, 4 * kE}, {0, 1, 4 * kE}, {0, -2, -kE},
                              {0, 2, -kE},    {-1, -1, -kE},   {1, -1, -kE},   {-1, 1, -kE},
                              {1, 1, -kE},    {-2, 0, kE / 2}, {2, 0, kE / 2}};
constexpr Tap kMhcDiagonal[] = {{0, 0, 6 * kE},     {-1, -1, 2 * kE},    {1, -1, 2 * kE},
                                {-1, 1, 2 * kE},    {1, 1, 2 * kE},      {-2, 0, -1.5f * kE},
                                {2, 0, -1.5f * kE}, {0, -2, -1.5f * kE}, {0, 2, -1.5f * kE}};

struct KernelSet {
  std::span<const Tap> green, row, column, diagonal;
};

// Whole-sample symmetric reflection into [0, n): period 2(n − 1), parity preserved.
int mirror(int i, int n) {
  if (n == 1) return 0;
  const int period = 2 * (n - 1);
  i %= period;
  if (i < 0) i += period;
  return i < n ? i : period - i;
}

int channelNamed(const CfaLayout& cfa, const char* name) {
  for (size_t i = 0; i < cfa.channels.size(); ++i)
    if (cfa.channels[i] == name) return static_cast<int>(i);
  return -1;
}

}  // namespace

bool isBayer(const CfaLayout& cfa) {
  if (cfa.width != 2 || cfa.height != 2 || cfa.tile.size() != 4 || cfa.channels.size() != 3)
    return false;
  const int r = channelNamed(cfa, "R"), g = channelNamed(cfa, "G"), b = channelNamed(cfa, "B");
  if (r < 0 || g < 0 || b < 0) return false;
  const std::vector<int>& t = cfa.tile;
  // Tile positions 0, 3 and 1, 2 are the diagonals.
  const bool greenMain =
      t[0] == g && t[3] == g && ((t[1] == r && t[2] == b) || (t[1] == b && t[2] == r));
  const bool greenAnti =
      t[1] == g && t[2] == g && ((t[0] == r && t[3] == b) || (t[0] == b && t[3] == r));
  return greenMain || greenAnti;
}

Image demosaic(const Image& mosaic, const CfaLayout& cfa, DemosaicMethod method) {
  if (cfa.isMonochrome() || cfa.isStacked()) return mosaic;
  if (!isBayer(cfa))
    throw InputError(
        {}, "cfa",
        "demosaicking needs a Bayer layout (RGGB, BGGR, GRBG, GBRG), not '" + cfa.name + "'");
  if (mosaic.channelCount() != 1)
    throw InputError({}, "",
                     "a mosaic has one channel, got " + std::to_string(mosaic.channelCount()));
  const int green = channelNamed(cfa, "G");
  const KernelSet k =
      method == DemosaicMethod::kBilinear
          ? KernelSet{kBilinearGreen, kBilinearRow, kBilinearColumn, kBilinearDiagonal}
          : KernelSet{kMhcGreen, kMhcRow, kMhcColumn, kMhcDiagonal};
  const int w = mosaic.width, h = mosaic.height;
  Image out(w, h, cfa.channels);
  if (w == 0 || h == 0) return out;

  auto apply = [&](std::span<const Tap> taps, int x, int y) {
    float sum = 0.0f;
    for (const Tap& t : taps)
      sum += t.weight * mosaic.at(mirror(x + t.dx, w), mirror(y + t.dy, h), 0);
    return sum;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int own = cfa.channelAt(x, y);
      for (int c = 0; c < 3; ++c) {
        float v;
        if (c == own)
          v = mosaic.at(x, y, 0);
        else if (c == green)
          v = apply(k.green, x, y);
        else if (own != green)
          v = apply(k.diagonal, x, y);  // R at B or B at R
        else
          v = apply(cfa.channelAt(x + 1, y) == c ? k.row : k.column, x, y);
        out.at(x, y, c) = v;
      }
    }
  return out;
}

}  // namespace camsim
