// The runtime's clock (steady, ns) and a sleep that wakes on time: the OS sleep up to a margin
// before the deadline, then a spin on the clock (sleep overshoot is tens of microseconds).
#pragma once

#include <chrono>
#include <cstdint>
#include <thread>

namespace dentsph::haptics {

inline std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Sleeps until `deadline_ns` (now_ns clock): plain sleep to `spin_ns` before it, then spins.
inline void sleep_until_ns(std::int64_t deadline_ns, std::int64_t spin_ns = 50'000) {
  const std::int64_t wake = deadline_ns - spin_ns;
  if (now_ns() < wake)
    std::this_thread::sleep_until(std::chrono::steady_clock::time_point(std::chrono::nanoseconds(wake)));
  while (now_ns() < deadline_ns) {
  }
}

}  // namespace dentsph::haptics
