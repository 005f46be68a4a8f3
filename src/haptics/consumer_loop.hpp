// The consumer loop: at the snapshot rate (30 to 60 Hz) takes the newest particle snapshot and
// hands it to a callback (a renderer, a recorder), measuring the rate and the snapshots' age.
#pragma once

#include "dentsph/haptics.hpp"
#include "haptics/shared.hpp"
#include "haptics/timing_stats.hpp"

namespace dentsph::haptics {

class ConsumerLoop {
 public:
  ConsumerLoop(const RealtimeOptions& options, RuntimeShared& shared) : opt_(options), shared_(shared) {}
  void run(std::int64_t t0_ns);
  ConsumerReport report() const;

 private:
  const RealtimeOptions& opt_;
  RuntimeShared& shared_;
  DurationHistogram ages_{1e6};
  ConsumerReport rep_;
  std::int64_t first_ns_ = 0, last_ns_ = 0;
};

}  // namespace dentsph::haptics
