// The last stage before a device: whatever the renderer computed, the force sent is finite, at
// most the profile's magnitude, and changes by at most max_force_rate * dt per tick.
#pragma once

#include <cstdint>

#include "dentsph/haptics/device.hpp"

namespace dentsph::haptics {

class ForceLimiter {
 public:
  explicit ForceLimiter(const DeviceProfile& profile);
  struct Result {
    Vec3 force;
    bool magnitude_limited = false, rate_limited = false, non_finite = false;
  };
  // The force to send this tick, dt_s after the previous one.
  Result apply(const Vec3& wanted, double dt_s);
  const Vec3& last() const { return last_; }
  void reset() { last_ = {}; }

 private:
  double max_force_, max_rate_;
  Vec3 last_;
};

// The profile whose "force" is the device's torque (N m): its limit, and 100 times the limit a
// second of change (a tenth a tick at 1 kHz); for a ForceLimiter of the torque. Only for a profile
// with max_torque_N_m > 0.
DeviceProfile torque_profile(const DeviceProfile& profile);

// The force with its magnitude capped at max_N (direction kept); zero when not finite.
Vec3 clamp_magnitude(const Vec3& f, double max_N);

}  // namespace dentsph::haptics
