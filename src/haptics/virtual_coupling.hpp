// Virtual coupling (Colgate et al. 1995): a proxy of mass m tied to the device by a spring k and
// a damper b, pushed by the simulated tool force and slowed by a drag c. Integrated implicitly
// (backward Euler on the linear terms), so it is stable at any stiffness and haptic rate; the
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
  void reset(const Vec3& position) { x_ = position, v_ = {}; }
  // One tick of dt s: device position and velocity (device frame), the tool force on the proxy
  // (device N). Moves the proxy; the force on the hand is coupling_force() of its new state. A new
  // device session announced on CouplingParams::sessions first puts the proxy where that session's
  // device started, at rest: a new hand does not inherit the previous one's tool.
  void step(const Vec3& device_x, const Vec3& device_v, const Vec3& tool_force, double dt);
  const Vec3& position() const { return x_; }
  const Vec3& velocity() const { return v_; }

 private:
  CouplingParams p_;
  Vec3 x_, v_;
  std::uint32_t session_ = 0;
};

}  // namespace dentsph::haptics
