// Virtual coupling (Colgate et al. 1995): a proxy of mass m tied to the device by a spring k and
// a damper b, pushed by the simulated tool force and slowed by a drag c. Integrated implicitly
// (backward Euler on the linear terms), so it is stable at any stiffness and haptic rate. The tool
// force comes from the last simulation step, so it is taken implicitly through its stiffness
// along the proxy's motion, estimated from the last two steps (the force's change against the
// proxy's move, at least kMinMove apart): F(x') = F - K (x' - x). Explicit, a contact of
// stiffness K is stable only while K dt^2 < 4 m: at the iisph solver's 1 ms step the flat
// plugger on paste (about 4e6 N/m at the device) returned a force of alternating sign every step,
// 250 to 300 Hz in the rendered force. In contact the estimate decays by half every
// kStiffnessHalfLife steps once the contact stiffens no more (the discrete loop is stable while it
// stays above half the contact's stiffness less 2 m / dt^2); without a tool force it is zero. It
// only adds dissipation; the
// proxy is the simulated tool: the simulation loop steps it with its own dt, so the tool never
// moves faster than the coupling pulls it, however slow the simulation; the haptic loop renders
// the coupling force with the device's newest position (force_renderer.cpp).
#pragma once

#include <cstdint>

#include "dentsph/haptics.hpp"

namespace dentsph::haptics {

// The spring and damper's force on the hand: the proxy at proxy_x moving at proxy_v, the device
// at device_x moving at device_v (device frame, N). The one formula of the coupling force: the
// haptic loop renders it with the device's newest position (force_renderer.cpp).
inline Vec3 coupling_force(const CouplingParams& p, const Vec3& proxy_x, const Vec3& proxy_v, const Vec3& device_x,
                           const Vec3& device_v) {
  return p.stiffness_N_per_m * (proxy_x - device_x) + p.damping_N_s_per_m * (proxy_v - device_v);
}

class VirtualCoupling {
 public:
  explicit VirtualCoupling(const CouplingParams& p);
  void reset(const Vec3& position) { x_ = position, v_ = {}, sampled_ = false, k_tool_ = 0; }
  // Puts the proxy at `position` moving at `velocity` (at most the speed limit): a free move,
  // where nothing within reach of the instrument's path holds it back (sim_loop.cpp). The tool
  // force's stiffness is sampled afresh from there.
  void place(const Vec3& position, const Vec3& velocity);
  // Keeps the proxy on the outer side of the plane through `point` with unit `normal` (a rigid
  // surface the hand's instrument rests on): moved back onto it, its velocity into it removed.
  void keep_outside(const Vec3& point, const Vec3& normal);
  // One tick of dt s: device position and velocity (device frame), the tool force on the proxy
  // (device N). Moves the proxy; the force on the hand is coupling_force() of its new state.
  void step(const Vec3& device_x, const Vec3& device_v, const Vec3& tool_force, double dt);
  const Vec3& position() const { return x_; }
  const Vec3& velocity() const { return v_; }
  // The tool force's stiffness (device N/m) the last step took implicitly.
  double tool_stiffness() const { return k_tool_; }

  static constexpr double kMinMove = 1e-8;         // m at the device between two samples of the stiffness
  static constexpr double kStiffnessHalfLife = 64;  // steps in contact

 private:
  CouplingParams p_;
  Vec3 x_, v_;
  Vec3 sampled_x_, sampled_force_;  // where the stiffness was last sampled, and the tool force there
  bool sampled_ = false;
  double k_tool_ = 0;
};

}  // namespace dentsph::haptics
