#include "integrator/camera/shutter.h"

#include <algorithm>
#include <cmath>

#include "sensor/base/check.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {

Shutter::Shutter(std::vector<double> times, std::vector<double> efficiency, Type type,
                 double rowTime)
    : times_(std::move(times)), values_(std::move(efficiency)), type_(type), rowTime_(rowTime) {
  CAMSIM_CHECK(times_.size() >= 2 && times_.size() == values_.size());
  cdf_.assign(times_.size(), 0.0);
  for (size_t i = 1; i < times_.size(); ++i) {
    CAMSIM_CHECK(times_[i] > times_[i - 1] && values_[i] >= 0.0);
    cdf_[i] = cdf_[i - 1] + 0.5 * (values_[i] + values_[i - 1]) * (times_[i] - times_[i - 1]);
  }
  total_ = cdf_.back();
  CAMSIM_CHECK(total_ > 0.0);
}

Shutter Shutter::box(double open, double close) {
  return Shutter({open, close}, {1.0, 1.0}, Type::kGlobal, 0.0);
}

Shutter Shutter::trapezoid(double open, double close, double rampOpen, double rampClose, Type type,
                           double rowTime) {
  // Knots strictly inside (open, close) only: a ramp that fills the exposure ends at close
  // itself, and one lost to rounding (open + 1e-20 == open) is no ramp (two equal knot
  // times aborted the process).
  const double a = open + rampOpen, b = close - rampClose;
  bool up = rampOpen > 0.0 && a > open, down = rampClose > 0.0 && b < close;
  // Both ramps and no time between them to peak at (an exposure of one or two ulps): a box.
  const double mid = 0.5 * (open + close);
  if (up && down && !(a < close) && !(b > open) && !(mid > open && mid < close)) up = down = false;
  std::vector<double> t = {open}, s = {up ? 0.0 : 1.0};
  if (up && a < close) t.push_back(a), s.push_back(1.0);
  if (down && b > t.back()) t.push_back(b), s.push_back(1.0);
  if (up && down && t.size() == 1) t.push_back(mid), s.push_back(1.0);
  t.push_back(close), s.push_back(down ? 0.0 : 1.0);
  return Shutter(std::move(t), std::move(s), type, rowTime);
}

namespace {

// Knot times moved by scaled() or shifted() must stay apart: an exposure too short for the
// time it opens at (1e-17 s at 0.5 s: 0.5 + 1e-17 == 0.5) cannot be represented.
void checkApart(const std::vector<double>& t, double exposure) {
  for (size_t i = 1; i < t.size(); ++i)
    if (!(t[i] > t[i - 1]))
      throw InputError({}, "shutter",
                       "the exposure, " + formatShortest(exposure) +
                           " s, is too short for the time it opens at, " +
                           formatShortest(t.front()) +
                           " s (double precision cannot tell its times apart)");
}

}  // namespace

Shutter Shutter::scaled(double k) const {
  CAMSIM_CHECK(k > 0.0);
  std::vector<double> t = times_;
  for (double& v : t) v = times_.front() + (v - times_.front()) * k;
  checkApart(t, (times_.back() - times_.front()) * k);
  return Shutter(std::move(t), values_, type_, rowTime_);
}

Shutter Shutter::shifted(double dt) const {
  std::vector<double> t = times_;
  for (double& v : t) v += dt;
  checkApart(t, times_.back() - times_.front());
  return Shutter(std::move(t), values_, type_, rowTime_);
}

double Shutter::efficiency(double t) const {
  if (t < times_.front() || t > times_.back()) return 0.0;
  const size_t i = std::min<size_t>(
      static_cast<size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()),
      times_.size() - 1);
  const double f = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
  return values_[i - 1] + f * (values_[i] - values_[i - 1]);
}

double Shutter::sample(double u) const {
  const double target = u * total_;
  size_t i = static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin());
  i = std::clamp<size_t>(i, 1, times_.size() - 1);
  // Within segment i−1..i the density is linear: s(x) = a + b x, x = t − t_{i−1};
  // solve a x + b x²/2 = r for x.
  const double a = values_[i - 1], dt = times_[i] - times_[i - 1];
  const double b = (values_[i] - a) / dt;
  const double r = std::max(0.0, target - cdf_[i - 1]);
  double x;
  if (std::abs(b) < 1e-12 * std::max(a, 1e-300) / dt) {
    x = a > 0.0 ? r / a : 0.0;
  } else {
    const double disc = std::max(0.0, a * a + 2.0 * b * r);
    x = r > 0.0 ? 2.0 * r / (a + std::sqrt(disc)) : 0.0;  // root of b/2 x² + a x − r = 0
  }
  return times_[i - 1] + std::clamp(x, 0.0, dt);
}

}  // namespace camsim
