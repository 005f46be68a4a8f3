// Time-domain passivity control (Hannaford & Ryu 2002, "Time-domain passivity control of haptic
// interfaces", IEEE Trans. Robotics and Automation 18(1)): the haptic loop observes the energy its
// forces have done on the hand, and where the device has given the hand more than it took (a late
// simulation, a long tick on a loaded machine), it adds the damping that takes the excess back over
// the next tick. A passive rendering is sent unchanged: the control acts only on energy given beyond
// kTolerance of what the hand has put in (so that the small excursions of a rendering that is
// passive on the whole do not switch a damper on and off, which a hand feels as buzz).
#pragma once

#include <cstdint>

#include "dentsph/vec3.hpp"

namespace dentsph::haptics {

class PassivityControl {
 public:
  // The hand at `x` (device frame, m) this tick: the force sent last did dot(f, x - x_last) on it.
  void observe(const Vec3& x);
  // `f` (N) with the damping against the hand's velocity `v` (m/s) that takes the observed excess
  // (E beyond kTolerance of the hand's work) back over a tick of `dt` s: f - alpha v, alpha =
  // excess / (|v|^2 dt) up to kMaxDamping (where the hand is slow, as at a reversal, the excess is
  // taken back over several ticks instead of by one jolt); `f` itself where there is no excess,
  // the hand is at rest or dt is not positive.
  Vec3 correct(const Vec3& f, const Vec3& v, double dt);
  // The force sent this tick (after the limits), which the next observe() accounts for.
  void sent(const Vec3& f) { last_f_ = f; }
  // A new session: nothing observed, nothing owed.
  void reset();

  // N s/m: the most damping the control adds, about what a desktop device renders without
  // buzzing (the virtual coupling's own is 2).
  static constexpr double kMaxDamping = 10;
  // The share of the energy the hand has put in that the device may give back before the control
  // acts: half the 1% the runtime's passivity tests allow.
  static constexpr double kTolerance = 0.005;

  double energy_J() const { return e_; }                   // done on the hand so far (< 0: it took energy)
  std::uint64_t damped_ticks() const { return damped_; }  // ticks correct() added damping

 private:
  Vec3 last_x_, last_f_;
  bool have_x_ = false;
  double e_ = 0;
  double taken_ = 0;  // J, the hand's work the forces took in (each tick's where it was negative)
  std::uint64_t damped_ = 0;
};

}  // namespace dentsph::haptics
