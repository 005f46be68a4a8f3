// Turns a force that changes at the simulation's rate into one that is continuous at the haptic
// rate: each new sample is approached linearly over the measured interval between samples, from
// the value rendered when it arrived. The rendered force lags the simulation by one sample
// interval and never jumps, however slow the simulation.
#pragma once

#include <cstdint>

#include "dentsph/vec3.hpp"

namespace dentsph::haptics {

class ForceInterpolator {
 public:
  // A new sample at time now_ns.
  void add(const Vec3& sample, std::int64_t now_ns);
  // The value at now_ns.
  Vec3 at(std::int64_t now_ns) const;
  double interval_s() const { return interval_s_; }

 private:
  Vec3 from_, to_;
  std::int64_t start_ns_ = 0, last_sample_ns_ = -1;
  double interval_s_ = 0.001;  // filtered interval between samples
  std::uint64_t intervals_ = 0;
};

}  // namespace dentsph::haptics
