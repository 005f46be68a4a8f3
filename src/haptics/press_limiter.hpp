// PressLimiter: at most N presses of a device button counted in any one second (a bouncing
// switch, or a client that toggles a bit at the device's rate, would otherwise dispense or switch
// the light a thousand times a second); the others are refused and counted. No allocation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace dentsph::haptics {

template <int N>
class PressLimiter {
 public:
  // A press at `now_ns`: true when it counts (fewer than N counted in the second before it).
  bool press(std::int64_t now_ns) {
    const std::int64_t oldest = at_ns_[next_];  // the N-th last press counted
    if (counted_ >= std::uint64_t(N) && now_ns - oldest < 1'000'000'000) {
      ++refused_;
      return false;
    }
    at_ns_[next_] = now_ns;
    next_ = (next_ + 1) % std::size_t(N);
    ++counted_;
    return true;
  }
  std::uint64_t counted() const { return counted_; }
  std::uint64_t refused() const { return refused_; }

 private:
  std::array<std::int64_t, N> at_ns_{};  // the last N presses counted, the oldest at next_
  std::size_t next_ = 0;
  std::uint64_t counted_ = 0, refused_ = 0;
};

}  // namespace dentsph::haptics
