// free_air_force (haptics.hpp): the force rendered while the instrument touched nothing.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "dentsph/haptics.hpp"

namespace dentsph {

namespace {

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / double(v.size());
}

// The 95th percentile (nearest rank).
double p95(std::vector<double> v) {
  if (v.empty()) return 0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(0.95 * double(v.size())));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

}  // namespace

FreeAirForce free_air_force(const Recording& r, double window_s) {
  FreeAirForce f;
  f.window_s = window_s;
  // Steps in wall-time order (the simulation loop records them so); for each tick, the steps
  // within (t - window, t] are a contiguous range.
  const std::vector<StepSample>& steps = r.steps;
  std::vector<double> free, contact;
  std::size_t begin = 0, end = 0;  // [begin, end): steps with wall_t in (t - window, t]
  std::size_t touching = 0;        // of those, the steps with a tool force
  auto touches = [&](std::size_t k) { return norm2(steps[k].tool_force) > 0; };
  for (const HapticSample& tick : r.haptic) {
    while (end < steps.size() && steps[end].wall_t <= tick.t) touching += touches(end++);
    while (begin < end && steps[begin].wall_t <= tick.t - window_s) touching -= touches(begin++);
    if (begin == end) continue;  // no step in the window: neither
    // The hard contact touching (the tooth, set paste) is contact too, though the simulated tool
    // feels nothing there.
    (touching > 0 || norm2(tick.contact_force) > 0 ? contact : free).push_back(norm(tick.force));
  }
  f.free_ticks = free.size();
  f.contact_ticks = contact.size();
  f.free_mean_N = mean(free);
  f.contact_mean_N = mean(contact);
  f.free_p95_N = p95(std::move(free));
  f.contact_p95_N = p95(std::move(contact));
  return f;
}

}  // namespace dentsph
