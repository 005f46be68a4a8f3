// Lock-free exchange between two threads: a triple buffer. One writer fills its back buffer and
// publishes it; one reader takes the newest published buffer. Neither ever waits for the other,
// nothing is allocated after construction, and the reader always sees a complete value (the
// newest one). Used for the device pose (haptic -> simulation), the simulation output
// (simulation -> haptic) and particle snapshots (simulation -> consumer).
#pragma once

#include <atomic>
#include <cstdint>

namespace dentsph::haptics {

template <class T>
class TripleBuffer {
 public:
  TripleBuffer() = default;
  // Every buffer starts as a copy of `initial` (snapshots: preallocated vectors).
  explicit TripleBuffer(const T& initial) : buffers_{initial, initial, initial} {}
  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;

  // ---- writer thread -------------------------------------------------------------------------
  T& back() { return buffers_[back_]; }
  // Makes the back buffer the newest value and takes the previous middle one as the next back.
  // Release: everything written to back() before is visible to the reader that takes it.
  void publish() {
    back_ = std::uint8_t(middle_.exchange(std::uint8_t(back_ | kFresh), std::memory_order_acq_rel) & kIndex);
  }

  // ---- reader thread -------------------------------------------------------------------------
  // Takes the newest published value if there is one the reader has not taken; returns whether it
  // did. Acquire: the writer's writes to that buffer are visible; release: the reader's reads of
  // the buffer it hands back are done before the writer reuses it.
  bool update() {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    front_ = std::uint8_t(middle_.exchange(front_, std::memory_order_acq_rel) & kIndex);
    return true;
  }
  const T& front() const { return buffers_[front_]; }

 private:
  static constexpr std::uint8_t kIndex = 0x3, kFresh = 0x4;
  T buffers_[3]{};
  std::uint8_t back_ = 0;                  // writer's
  std::atomic<std::uint8_t> middle_{1};    // shared: index | fresh bit
  std::uint8_t front_ = 2;                 // reader's
};

}  // namespace dentsph::haptics
