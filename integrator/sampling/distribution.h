// DiscreteDistribution: picks index i with probability w_i / Σw (alias-free: by counting
// the CDF values ≤ u for a few entries, by binary search on the CDF for more). Used for
// choosing lights by power and triangles by area.
#pragma once

#include <algorithm>
#include <span>
#include <vector>

#include "sensor/base/check.h"

namespace camsim {

class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  explicit DiscreteDistribution(std::span<const double> weights) {
    cdf_.resize(weights.size() + 1, 0.0);
    for (size_t i = 0; i < weights.size(); ++i) {
      CAMSIM_CHECK(weights[i] >= 0.0);
      cdf_[i + 1] = cdf_[i] + weights[i];
    }
    total_ = cdf_.back();
    if (total_ > 0.0)
      for (double& c : cdf_) c /= total_;
    pmf_.reserve(weights.size());
    for (size_t i = 0; i < weights.size(); ++i) {
      pmf_.push_back(static_cast<float>(cdf_[i + 1] - cdf_[i]));
      someZero_ = someZero_ || pmf_.back() == 0.0f;
    }
  }

  size_t size() const { return cdf_.empty() ? 0 : cdf_.size() - 1; }
  double total() const { return total_; }
  float pmf(size_t i) const { return pmf_[i]; }

  // Index for u in [0,1); *uRemapped gets u rescaled to [0,1) within the chosen bucket.
  size_t sample(float u, float* uRemapped = nullptr) const {
    CAMSIM_CHECK(total_ > 0.0);
    if (pmf_.size() == 1) {  // one light, triangle, …: what the general path gives, no divide
      if (uRemapped) *uRemapped = std::clamp(u, 0.0f, 0x1.fffffep-1f);
      return 0;
    }
    const double uu = static_cast<double>(u);
    size_t i;
    if (cdf_.size() <= kLinearSearchMax) {
      // A handful of entries (a light's triangles, a few lights): count the CDF values ≤ u
      // (what upper_bound finds) without the search's data-dependent branches.
      i = 0;
      for (size_t k = 1; k < cdf_.size(); ++k) i += cdf_[k] <= uu ? 1 : 0;
    } else {
      i = static_cast<size_t>(std::upper_bound(cdf_.begin() + 1, cdf_.end(), uu) - cdf_.begin()) -
          1;
    }
    i = std::min(i, size() - 1);
    if (someZero_)
      while (pmf(i) == 0.0f && i > 0) --i;  // never pick a zero-weight entry at a boundary
    if (uRemapped) {
      const double width = cdf_[i + 1] - cdf_[i];
      *uRemapped = width > 0.0
                       ? static_cast<float>(std::clamp((uu - cdf_[i]) / width, 0.0, 0x1.fffffep-1))
                       : 0.0f;
    }
    return i;
  }

 private:
  static constexpr size_t kLinearSearchMax = 9;
  std::vector<double> cdf_;
  std::vector<float> pmf_;  // (cdf_[i + 1] − cdf_[i]) in float, looked up on the hot path
  bool someZero_ = false;   // a zero pmf: sample() steps back from those
  double total_ = 0.0;
};

}  // namespace camsim
