#include "haptics/watchdog.hpp"

#include <algorithm>

namespace dentsph::haptics {

double Watchdog::update(double sim_age_s, double pose_age_s, double dt_s) {
  sim_stale_ = !(sim_age_s >= 0 && sim_age_s <= p_.sim_timeout_s);
  pose_stale_ = !(pose_age_s >= 0 && pose_age_s <= p_.pose_timeout_s);
  const bool fault = sim_stale_ || pose_stale_;
  if (fault && !fault_) ++trips_;
  fault_ = fault;
  if (fault)
    gain_ = p_.ramp_down_s > 0 ? std::max(0.0, gain_ - dt_s / p_.ramp_down_s) : 0.0;
  else
    gain_ = p_.ramp_up_s > 0 ? std::min(1.0, gain_ + dt_s / p_.ramp_up_s) : 1.0;
  return gain_;
}

}  // namespace dentsph::haptics
