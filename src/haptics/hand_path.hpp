// The path a scripted hand follows: the tool's keyframes as a hand moves through them. Followed
// literally, the keyframes' linear segments change velocity in no time at every keyframe, an
// acceleration no hand makes; the rendered force then carries the coupling proxy's kick at every
// corner even in air. A hand's voluntary movement has a bandwidth of a few hertz, so the scripted
// hand follows the keyframes through a critically damped second-order low-pass of corner
// frequency `hand_bandwidth_hz` (5 Hz): its velocity and acceleration are continuous, it lags the
// keyframes by 2 / omega (64 ms at 5 Hz) and otherwise follows each segment exactly.
//
// The position is the filter's exact response to the piecewise-linear path (a sum of ramp
// responses, one per change of velocity), so it is a function of time alone: no state, no
// allocation after construction. The orientation follows the keyframes delayed by the same lag.
#pragma once

#include <vector>

#include "dentsph/scene.hpp"

namespace dentsph::haptics {

inline constexpr double hand_bandwidth_hz = 5.0;

class HandPath {
 public:
  explicit HandPath(const ToolTrajectory& trajectory, double bandwidth_hz = hand_bandwidth_hz);
  // The pose (scene frame) t s after the trajectory's time 0.
  Pose at(double t) const;
  double lag_s() const { return 2.0 / omega_; }

 private:
  struct Corner {
    double t;   // s, the keyframe's time
    Vec3 dv;    // m/s, the change of velocity there
  };
  const ToolTrajectory& trajectory_;
  double omega_;                // rad/s
  std::vector<Corner> corners_;  // in time order
};

}  // namespace dentsph::haptics
