#include "haptics/passivity_control.hpp"

#include <algorithm>
#include <cmath>

namespace dentsph::haptics {

void PassivityControl::observe(const Vec3& x) {
  if (!is_finite(x)) return;
  if (have_x_) {
    const double w = dot(last_f_, x - last_x_);
    if (std::isfinite(w)) {
      e_ += w;
      if (w < 0) taken_ -= w;
    }
  }
  last_x_ = x;
  have_x_ = true;
}

Vec3 PassivityControl::correct(const Vec3& f, const Vec3& v, double dt) {
  const double excess = e_ - kTolerance * taken_;
  if (!(excess > 0) || !(dt > 0) || !is_finite(v)) return f;
  const double v2 = norm2(v);
  if (!(v2 > 0)) return f;
  // Finite: excess and v2 are, and an underflowed |v|^2 dt gives infinity, capped.
  const double alpha = std::min(excess / (v2 * dt), kMaxDamping);
  ++damped_;
  return f - v * alpha;
}

void PassivityControl::reset() {
  have_x_ = false;
  last_f_ = {};
  e_ = taken_ = 0;
}

}  // namespace dentsph::haptics
