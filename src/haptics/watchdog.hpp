// The force gain: 1 while the simulation output and the device pose are fresh; after either goes
// stale it ramps linearly to 0 (ramp_down_s), and back to 1 (ramp_up_s) once both are fresh.
#pragma once

#include <cstdint>

#include "dentsph/haptics.hpp"

namespace dentsph::haptics {

class Watchdog {
 public:
  explicit Watchdog(const WatchdogParams& p) : p_(p) {}
  // Ages in s of the newest simulation output and device pose (negative: none yet); returns the
  // gain for this tick.
  double update(double sim_age_s, double pose_age_s, double dt_s);
  // A new device session: the gain starts again from zero and ramps up (ramp_up_s) once both are
  // fresh, so that a new hand is never met by the full force at once.
  void restart() { gain_ = 0; }
  bool sim_stale() const { return sim_stale_; }
  bool pose_stale() const { return pose_stale_; }
  std::uint64_t trips() const { return trips_; }

 private:
  WatchdogParams p_;
  double gain_ = 0;  // starts at zero: ramps up once both are fresh
  bool sim_stale_ = true, pose_stale_ = true, fault_ = true;
  std::uint64_t trips_ = 0;
};

}  // namespace dentsph::haptics
