// Turns a quantity that changes at the simulation's rate (a force, the proxy) into one that is
// continuous at the haptic rate: the samples, each stamped with the time it was made, are played
// back as a piecewise-linear curve a fixed delay behind the clock (the interval between samples and
// the longest they took to be seen), so that samples made at a step's regular pace but seen on the
// haptic loop's ticks (1.5 ms steps on 1 ms ticks: seen 1 and 2 ticks apart in turn) play back at
// their pace, without a ripple at the beat of the two rates. The playback clock slews to that delay
// at between half and one and a half times the real rate, so it never jumps; where no sample is
// there to play (the simulation late), the last value holds and the next one is approached from it.
// Fixed storage: no allocation.
#pragma once

#include <array>
#include <cstdint>

#include "dentsph/vec3.hpp"

namespace dentsph::haptics {

class ForceInterpolator {
 public:
  // A new sample made at made_ns and seen at now_ns (>= made_ns; same clock).
  void add(const Vec3& sample, std::int64_t now_ns, std::int64_t made_ns);
  // One seen as it is made.
  void add(const Vec3& sample, std::int64_t now_ns) { add(sample, now_ns, now_ns); }
  // The value at now_ns.
  Vec3 at(std::int64_t now_ns) const;
  double interval_s() const { return interval_s_; }  // filtered interval between samples' made times
  double delay_s() const { return interval_s_ + lag_s_; }  // the delay the playback slews to

 private:
  struct Point {
    Vec3 value;
    double t = 0;  // s after base_ns_, on the playback clock
  };
  static constexpr int kKept = 8;
  double seconds(std::int64_t ns) const { return double(ns - base_ns_) * 1e-9; }
  double play(double now_s) const { return play_anchor_ + (now_s - now_anchor_) * rate_; }
  Vec3 value(double t) const;
  void push(const Point& p);

  std::array<Point, kKept> kept_{};  // oldest first
  int count_ = 0;
  std::int64_t base_ns_ = 0, last_made_ns_ = 0;
  double play_anchor_ = 0, now_anchor_ = 0, rate_ = 1;  // playback time = anchor + (now - now anchor) rate
  double interval_s_ = 0.001;  // filtered interval between samples
  double lag_s_ = 0;           // the longest a sample took to be seen, decaying
  std::uint64_t intervals_ = 0;
};

}  // namespace dentsph::haptics
