// The force for the hand, per mode. Direct (the paper's): the tool is where the device is and the
// hand feels the simulated tool force. Virtual coupling: the tool is the proxy the simulation
// moves (sim_loop.cpp); the hand feels the spring and damper between the proxy and the device,
// computed here at the haptic rate with the device's newest position. What comes from the
// simulation (force, proxy) is interpolated so that it never jumps, however slow the simulation.
// The proxy so rendered is where the simulation put it for a device pose some milliseconds old
// (the step's wait and run, and the interpolation's one interval): it is carried forward to now
// along its motion per second of the device's clock over the last outputs (by at most kMaxLead),
// so that a proxy moving with the hand in air is not
// felt as a drag of stiffness x speed x latency (0.075 N at 62.5 mm/s and 3 ms on 400 N/m). A
// proxy held by the paste has no velocity to carry. Where the newest output was a free move (no
// paste or wall particle within reach of the instrument's path: the proxy went where the hand is) the coupling
// renders nothing, so that a quick move through air drags nothing; on entering paste from such a
// move the proxy's motion is not carried forward (it has just stopped going with the hand) and the
// coupling's force ramps in over kEntryRamp, so that the latency of the outputs (the hand a few
// millimetres on at 0.5 m/s) is not one step of force. The result still passes the
// watchdog and the limiter.
#pragma once

#include <cstdint>

#include "dentsph/haptics.hpp"
#include "haptics/force_interpolator.hpp"
#include "haptics/messages.hpp"

namespace dentsph::haptics {

class ForceRenderer {
 public:
  ForceRenderer(ForceMode mode, const CouplingParams& coupling) : mode_(mode), coupling_(coupling) {}
  // A new simulation output (finite) at now_ns.
  void add(const SimOutput& o, std::int64_t now_ns);
  // The force on the hand at now_ns for the device at x moving at v (device frame).
  Vec3 render(const Vec3& x, const Vec3& v, std::int64_t now_ns) const;
  // Forgets the simulation's outputs (a new device session): no force until the next one, which
  // is then taken as it is, not approached from the previous session's proxy or force.
  void restart() {
    force_ = proxy_x_ = proxy_w_ = stamp_ = ForceInterpolator{};
    motion_ = {};
    started_ = false;
    free_ = false;
    entered_ns_ = -1;
  }
  // The newest output was a free move (SimOutput::free): the coupling renders nothing.
  bool free() const { return free_; }
  // The proxy (coupling) or the device (direct) position now.
  Vec3 tool_position(const Vec3& x, std::int64_t now_ns) const {
    return mode_ == ForceMode::coupling && started_ ? proxy_x_.at(now_ns) : x;
  }

 private:
  ForceMode mode_;
  CouplingParams coupling_;
  // The proxy carried forward from the device pose it followed to now_ns.
  Vec3 proxy_now(std::int64_t now_ns) const;
  static constexpr double kMaxLead = 0.02;       // s
  static constexpr double kMinStampStep = 2e-4;  // s, between device poses the motion is taken over
  ForceInterpolator force_, proxy_x_;
  ForceInterpolator proxy_w_;  // the proxy's motion per second of device time (its velocity here)
  ForceInterpolator stamp_;    // x: the stamp (s after base_ns_) of the device pose each proxy followed
  Vec3 motion_, last_x_;
  double last_stamp_s_ = 0;
  std::int64_t base_ns_ = 0;
  bool started_ = false;
  bool free_ = false;
  std::int64_t entered_ns_ = -1;  // when the outputs stopped being free moves (paste entered)
  static constexpr double kEntryRamp = 0.01;  // s: the coupling's force ramps in over this on entering paste
};

}  // namespace dentsph::haptics
