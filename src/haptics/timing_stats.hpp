// Distributions of durations kept without allocation: a histogram of 1 us bins (up to 50 ms,
// longer ones in an overflow bin), the exact maximum and the count. add() is O(1) and
// allocation-free, for use inside the haptic loop.
#pragma once

#include <cstdint>
#include <vector>

namespace dentsph::haptics {

class DurationHistogram {
 public:
  explicit DurationHistogram(double max_us = 50'000) : bins_(std::size_t(max_us) + 1, 0) {}
  void add(double us) {
    if (!(us >= 0)) us = 0;
    const std::size_t b = us >= double(bins_.size() - 1) ? bins_.size() - 1 : std::size_t(us);
    ++bins_[b];
    ++count_;
    if (us > max_) max_ = us;
  }
  std::uint64_t count() const { return count_; }
  double max() const { return max_; }
  // The q-quantile (0..1) to 1 us: the upper edge of the bin holding it, capped at the maximum.
  double quantile(double q) const;

 private:
  std::vector<std::uint32_t> bins_;
  std::uint64_t count_ = 0;
  double max_ = 0;
};

}  // namespace dentsph::haptics
