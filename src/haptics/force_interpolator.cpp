#include "haptics/force_interpolator.hpp"

#include <algorithm>

namespace dentsph::haptics {

namespace {
constexpr double kMinInterval = 2e-4, kMaxInterval = 0.05;  // s
constexpr double kFilter = 0.2;                             // weight of a new interval
constexpr double kLagDecay = 0.99;                          // per sample, of the longest lag seen
constexpr double kSlew = 0.01;  // s: a playback delay this far from its target changes the rate by 1
constexpr double kMaxSlew = 0.5;
constexpr double kRepeat = 1e-6;  // s after the newest, for a sample made no later
}  // namespace

void ForceInterpolator::push(const Point& p) {
  if (count_ == kKept) {
    std::copy(kept_.begin() + 1, kept_.end(), kept_.begin());
    --count_;
  }
  kept_[count_++] = p;
}

Vec3 ForceInterpolator::value(double t) const {
  if (t <= kept_[0].t) return kept_[0].value;
  for (int k = 1; k < count_; ++k)
    if (t <= kept_[k].t) {
      const Point &a = kept_[k - 1], &b = kept_[k];
      return a.value + (b.value - a.value) * ((t - a.t) / (b.t - a.t));
    }
  return kept_[count_ - 1].value;  // past the newest: it holds
}

void ForceInterpolator::add(const Vec3& sample, std::int64_t now_ns, std::int64_t made_ns) {
  made_ns = std::min(made_ns, now_ns);
  if (count_ == 0) {  // the first: taken as it is
    base_ns_ = last_made_ns_ = made_ns;
    kept_[0] = {sample, 0};
    count_ = 1;
    play_anchor_ = now_anchor_ = seconds(now_ns);
    rate_ = 1;
    return;
  }
  const double now_s = seconds(now_ns);
  const double p = play(now_s);
  if (made_ns > last_made_ns_) {
    const double dt = double(made_ns - last_made_ns_) * 1e-9;
    const double w = intervals_++ == 0 ? 1.0 : kFilter;
    interval_s_ = std::clamp((1 - w) * interval_s_ + w * dt, kMinInterval, kMaxInterval);
    last_made_ns_ = made_ns;
  }
  lag_s_ = std::max(lag_s_ * kLagDecay, double(now_ns - made_ns) * 1e-9);
  // Past the newest sample (the simulation late): the output held; it goes on from where it is, to
  // the new sample at its made time (a delay behind the clock: about an interval after the playback).
  // A sample made before what plays (seen later than the delay) or before the newest (a repeat)
  // follows it at once.
  if (kept_[count_ - 1].t < p) push({value(p), p});
  push({sample, std::max(seconds(made_ns), kept_[count_ - 1].t + kRepeat)});
  // The playback clock, continuous, slews towards the target delay.
  const double behind = (now_s - delay_s()) - p;  // > 0: playing too far back
  rate_ = 1 + std::clamp(behind / kSlew, -kMaxSlew, kMaxSlew);
  play_anchor_ = p;
  now_anchor_ = now_s;
}

Vec3 ForceInterpolator::at(std::int64_t now_ns) const {
  if (count_ == 0) return {};
  return value(play(seconds(now_ns)));
}

}  // namespace dentsph::haptics
