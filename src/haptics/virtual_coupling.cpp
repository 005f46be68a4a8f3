#include "haptics/virtual_coupling.hpp"

#include "haptics/exchange.hpp"
#include "haptics/messages.hpp"

#include <algorithm>
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

void VirtualCoupling::place(const Vec3& position, const Vec3& velocity) {
  if (!is_finite(position) || !is_finite(velocity)) return;
  x_ = position;
  v_ = velocity;
  const double speed = norm(v_);
  if (p_.max_speed_m_per_s > 0 && speed > p_.max_speed_m_per_s) v_ *= p_.max_speed_m_per_s / speed;
  sampled_ = false;
}

void VirtualCoupling::keep_outside(const Vec3& point, const Vec3& normal) {
  const double into = dot(x_ - point, normal);
  if (!(into < 0)) return;
  x_ -= normal * into;
  const double vn = dot(v_, normal);
  if (vn < 0) v_ -= normal * vn;
}

void VirtualCoupling::step(const Vec3& xd, const Vec3& vd, const Vec3& tool_force, double dt) {
  // The drag takes energy out of a contact; in air (no tool force) it would only be felt, as a force
  // against the hand of drag x speed (0.125 N at 62.5 mm/s), so it acts in contact alone.
  const bool contact = tool_force != Vec3{};
  const double k = p_.stiffness_N_per_m, b = p_.damping_N_s_per_m, c = contact ? p_.proxy_drag_N_s_per_m : 0.0,
               m = p_.proxy_mass_kg;
  // The tool force was computed with the proxy where it is now. Its stiffness along the proxy's
  // move since the last sample: -dF . dx / |dx|^2 where it resists the move; the largest of that
  // and the decayed estimate.
  k_tool_ = contact ? k_tool_ * std::exp2(-1 / kStiffnessHalfLife) : 0;
  if (!sampled_) {
    sampled_x_ = x_, sampled_force_ = tool_force, sampled_ = true;
  } else if (const Vec3 dx = x_ - sampled_x_; norm2(dx) >= kMinMove * kMinMove) {
    const double resisting = -dot(tool_force - sampled_force_, dx) / norm2(dx);
    if (std::isfinite(resisting)) k_tool_ = std::max(k_tool_, resisting);
    sampled_x_ = x_, sampled_force_ = tool_force;
  }
  // m (v' - v) / dt = k (xd - x - dt v') + b (vd - v') - c v' + F - K dt v'   (x' = x + dt v')
  const Vec3 rhs = v_ + (k * (xd - x_) + b * vd + tool_force) * (dt / m);
  const double lhs = 1 + dt * (b + c) / m + dt * dt * (k + k_tool_) / m;
  Vec3 v = rhs / lhs;
  if (!is_finite(v)) return;  // keep the proxy where it is
  const double speed = norm(v);
  if (p_.max_speed_m_per_s > 0 && speed > p_.max_speed_m_per_s) v *= p_.max_speed_m_per_s / speed;
  v_ = v;
  x_ += v_ * dt;
}

}  // namespace dentsph::haptics
