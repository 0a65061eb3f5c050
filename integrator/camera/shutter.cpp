#include "integrator/camera/shutter.h"

#include <algorithm>
#include <cmath>

#include "sensor/base/check.h"

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
  std::vector<double> t = {open}, s = {rampOpen > 0.0 ? 0.0 : 1.0};
  if (rampOpen > 0.0) t.push_back(open + rampOpen), s.push_back(1.0);
  if (rampClose > 0.0 && close - rampClose > t.back())
    t.push_back(close - rampClose), s.push_back(1.0);
  t.push_back(close), s.push_back(rampClose > 0.0 ? 0.0 : 1.0);
  return Shutter(std::move(t), std::move(s), type, rowTime);
}

Shutter Shutter::scaled(double k) const {
  CAMSIM_CHECK(k > 0.0);
  std::vector<double> t = times_;
  for (double& v : t) v = times_.front() + (v - times_.front()) * k;
  return Shutter(std::move(t), values_, type_, rowTime_);
}

Shutter Shutter::shifted(double dt) const {
  std::vector<double> t = times_;
  for (double& v : t) v += dt;
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
