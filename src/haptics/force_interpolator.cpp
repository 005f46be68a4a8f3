#include "haptics/force_interpolator.hpp"

#include <algorithm>

namespace dentsph::haptics {

namespace {
constexpr double kMinInterval = 2e-4, kMaxInterval = 0.05;  // s
constexpr double kFilter = 0.2;                             // weight of a new interval
}  // namespace

void ForceInterpolator::add(const Vec3& sample, std::int64_t now_ns) {
  // Where the output is now, with the interval it was being spread over: taken after the
  // interval changed, an early sample would shorten it and make the output jump.
  const Vec3 current = last_sample_ns_ >= 0 ? at(now_ns) : sample;
  if (last_sample_ns_ >= 0) {
    const double dt = double(now_ns - last_sample_ns_) * 1e-9;
    const double w = intervals_++ == 0 ? 1.0 : kFilter;
    interval_s_ = std::clamp((1 - w) * interval_s_ + w * dt, kMinInterval, kMaxInterval);
  }
  from_ = current;
  to_ = sample;
  start_ns_ = now_ns;
  last_sample_ns_ = now_ns;
}

Vec3 ForceInterpolator::at(std::int64_t now_ns) const {
  const double s = std::clamp(double(now_ns - start_ns_) * 1e-9 / interval_s_, 0.0, 1.0);
  return from_ + (to_ - from_) * s;
}

}  // namespace dentsph::haptics
