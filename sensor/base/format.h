// Number formatting shared by the commands' printed reports and output metadata.
//   formatNumber(v, p)  printf "%.{p}g"  (p significant digits)
//   formatRange(lo, hi)  "[lo, hi]" (or "(lo, hi]"), 10 significant digits
//   formatFixed(v, d)   printf "%.{d}f"  (d decimals)
//   formatRate(r)       "12.35 M", "4.20 k" or "17.00 " (two decimals, SI prefix; for "…/s")
//   formatSize(w, h)    "512x512" (an image size in pixels)
//   formatSixDigits(v)  printf "%06lld": "000042", "1234567" (numbers in file and folder names)
#pragma once

#include <string>

namespace camsim {

std::string formatNumber(double v, int precision = 3);
// A range as an error message states it: "[0.5, 10000]", "(0, 1e+06]" (lo open), bounds
// with 10 significant digits.
std::string formatRange(double lo, double hi, bool loOpen = false);
std::string formatFixed(double v, int decimals);
// The shortest decimal that reads back as the same double (std::to_chars): for numbers that
// must round-trip exactly (scene text written back, override records, exported intrinsics).
std::string formatShortest(double v);
std::string formatRate(double perSecond);
std::string formatSize(int width, int height);
// The six-digit numbers of file and folder names (BOP's scene, image, annotation and obj ids,
// KITTI's image ids, a dataset's item folders): v zero-padded to six digits, more when it
// needs them.
std::string formatSixDigits(long long v);

}  // namespace camsim
