#include "haptics/timing_stats.hpp"

#include <algorithm>
#include <cmath>

namespace dentsph::haptics {

double DurationHistogram::quantile(double q) const {
  if (count_ == 0) return 0;
  const auto rank = std::uint64_t(std::ceil(std::clamp(q, 0.0, 1.0) * double(count_)));
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < bins_.size(); ++b) {
    seen += bins_[b];
    if (seen >= std::max<std::uint64_t>(rank, 1)) return b + 1 == bins_.size() ? max_ : std::min(double(b + 1), max_);
  }
  return max_;
}

}  // namespace dentsph::haptics
