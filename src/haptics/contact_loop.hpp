// The contact loop: rebuilds the hard contact's field when paste sets (or the instrument is
// switched) off the simulation's and the haptic loop's threads, and hands it to the haptic loop.
// The simulation loop sends what is rigid now (RigidInput) when it changed; this loop, polling
// every few milliseconds, recomputes the particles' grid (a few milliseconds for a cavity's worth
// of set paste) and the instrument's shape, and publishes the ContactWorld the haptic loop reads.
#pragma once

#include <cstdint>

#include "haptics/shared.hpp"

namespace dentsph::haptics {

class ContactLoop {
 public:
  // `shared.contact`'s slots must hold the runtime's initial world (its field's grid).
  explicit ContactLoop(RuntimeShared& shared) : shared_(shared) {}
  // Runs on the calling thread until shared.stop is set.
  void run();
  std::uint64_t rebuilds() const { return rebuilds_; }
  double build_max_ms() const { return build_max_ms_; }

 private:
  RuntimeShared& shared_;
  std::uint64_t rebuilds_ = 0;
  double build_max_ms_ = 0;
};

}  // namespace dentsph::haptics
