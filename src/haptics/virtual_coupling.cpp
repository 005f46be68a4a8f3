#include "haptics/virtual_coupling.hpp"

#include "haptics/exchange.hpp"
#include "haptics/messages.hpp"

#include <cmath>
#include <stdexcept>

namespace dentsph::haptics {

VirtualCoupling::VirtualCoupling(const CouplingParams& p) : p_(p) {
  if (!(p.stiffness_N_per_m > 0) || !(p.proxy_mass_kg > 0) || !(p.damping_N_s_per_m >= 0) || !(p.max_speed_m_per_s >= 0) ||
      !(p.proxy_drag_N_s_per_m >= 0) || !std::isfinite(p.stiffness_N_per_m + p.proxy_mass_kg + p.damping_N_s_per_m +
                                                        p.proxy_drag_N_s_per_m))
    throw std::invalid_argument(
        "virtual coupling: stiffness and proxy mass must be positive, damping and drag non-negative, all finite");
}

void VirtualCoupling::step(const Vec3& xd, const Vec3& vd, const Vec3& tool_force, double dt) {
  if (p_.sessions && p_.sessions->update() && p_.sessions->front().session != session_) {
    session_ = p_.sessions->front().session;
    reset(p_.sessions->front().device_position);
  }
  const double k = p_.stiffness_N_per_m, b = p_.damping_N_s_per_m, c = p_.proxy_drag_N_s_per_m, m = p_.proxy_mass_kg;
  // m (v' - v) / dt = k (xd - x - dt v') + b (vd - v') - c v' + F   (x' = x + dt v')
  const Vec3 rhs = v_ + (k * (xd - x_) + b * vd + tool_force) * (dt / m);
  const double lhs = 1 + dt * (b + c) / m + dt * dt * k / m;
  Vec3 v = rhs / lhs;
  if (!is_finite(v)) return;  // keep the proxy where it is
  const double speed = norm(v);
  if (p_.max_speed_m_per_s > 0 && speed > p_.max_speed_m_per_s) v *= p_.max_speed_m_per_s / speed;
  v_ = v;
  x_ += v_ * dt;
}

}  // namespace dentsph::haptics
