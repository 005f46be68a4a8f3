// Energy flowing from the device into the hand, from a recording.
#include "dentsph/haptics/replay.hpp"

namespace dentsph {

std::vector<double> energy_to_hand(const std::vector<HapticSample>& s) {
  std::vector<double> e(s.size(), 0.0);
  for (std::size_t k = 1; k + 1 < s.size(); ++k) {
    const double dt2 = s[k + 1].t - s[k - 1].t;
    const Vec3 v = dt2 > 0 ? (s[k + 1].device_position - s[k - 1].device_position) / dt2 : Vec3{};
    const double dt = 0.5 * dt2;  // the tick's share of time
    e[k] = e[k - 1] + dot(s[k].force, v) * dt;
  }
  if (s.size() > 1) e.back() = e[s.size() - 2];
  return e;
}

}  // namespace dentsph
