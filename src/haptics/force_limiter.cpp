#include "haptics/force_limiter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dentsph::haptics {

Vec3 clamp_magnitude(const Vec3& f, double max_N) {
  if (!is_finite(f)) return {};
  const double n = norm(f);
  return n > max_N ? f * (max_N / n) : f;
}

DeviceProfile torque_profile(const DeviceProfile& p) {
  DeviceProfile t = p;
  t.name = p.name + " (torque)";
  t.max_force_N = p.max_torque_N_m;
  t.max_force_rate_N_per_s = 100 * p.max_torque_N_m;
  return t;
}

ForceLimiter::ForceLimiter(const DeviceProfile& p) : max_force_(p.max_force_N), max_rate_(p.max_force_rate_N_per_s) {
  if (!(max_force_ > 0) || !std::isfinite(max_force_) || !(max_rate_ > 0) || !std::isfinite(max_rate_))
    throw std::invalid_argument("device profile '" + p.name +
                                "': max_force_N and max_force_rate_N_per_s must be positive and finite");
}

ForceLimiter::Result ForceLimiter::apply(const Vec3& wanted, double dt_s) {
  Result r;
  Vec3 f = wanted;
  if (!is_finite(f)) {
    r.non_finite = true;
    f = {};
  }
  if (norm(f) > max_force_) {
    r.magnitude_limited = true;
    f = clamp_magnitude(f, max_force_);
  }
  // Rate: move from the last force towards f by at most max_rate dt. Both lie in the ball of
  // radius max_force, so every point between them does too (convexity).
  const double max_step = max_rate_ * std::clamp(dt_s, 0.0, 0.1);
  const Vec3 d = f - last_;
  const double dn = norm(d);
  if (dn > max_step) {
    r.rate_limited = true;
    f = last_ + d * (max_step / dn);
  }
  f = clamp_magnitude(f, max_force_);  // rounding: never a hair above the limit
  last_ = f;
  r.force = f;
  return r;
}

}  // namespace dentsph::haptics
