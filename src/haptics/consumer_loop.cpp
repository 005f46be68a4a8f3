#include "haptics/consumer_loop.hpp"

#include <cmath>

#include "haptics/clock.hpp"

namespace dentsph::haptics {

void ConsumerLoop::run(std::int64_t t0_ns) {
  if (opt_.snapshot_rate_hz <= 0) return;
  const auto period = std::int64_t(std::llround(1e9 / opt_.snapshot_rate_hz));
  std::int64_t next = t0_ns + period;
  while (!shared_.stop.load(std::memory_order_relaxed)) {
    sleep_until_ns(next, 0);
    next += period;
    if (!shared_.snapshots.update()) continue;
    const std::int64_t now = now_ns();
    const Snapshot& s = shared_.snapshots.front();
    ages_.add(double(now - s.published_ns) * 1e-3);
    if (rep_.frames++ == 0) first_ns_ = now;
    last_ns_ = now;
    if (opt_.on_snapshot) opt_.on_snapshot(std::span<const Vec3>(s.positions.data(), s.count), s.sim_time);
  }
}

ConsumerReport ConsumerLoop::report() const {
  ConsumerReport r = rep_;
  const double span = double(last_ns_ - first_ns_) * 1e-9;
  r.rate_hz = span > 0 && r.frames > 1 ? double(r.frames - 1) / span : 0;
  r.snapshot_age_p99_us = ages_.quantile(0.99);
  return r;
}

}  // namespace dentsph::haptics
