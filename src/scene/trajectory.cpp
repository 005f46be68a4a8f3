// ToolTrajectory::at: the tool's pose at a time, from its keyframes.
#include <algorithm>

#include "dentsph/scene.hpp"

namespace dentsph {

Pose ToolTrajectory::at(real t) const {
  if (keyframes.empty()) return Pose{};
  // Held before the first and after the last keyframe (a NaN time also gets the first).
  if (!(t > keyframes.front().t)) return keyframes.front().pose;
  if (t >= keyframes.back().t) return keyframes.back().pose;
  // The segment [a.t, b.t) holding t: b is the first keyframe after t.
  const auto b = std::upper_bound(keyframes.begin(), keyframes.end(), t,
                                  [](real time, const ToolKeyframe& k) { return time < k.t; });
  const ToolKeyframe& a = *(b - 1);
  return interpolate(a.pose, b->pose, (t - a.t) / (b->t - a.t));
}

real ToolTrajectory::max_speed(const std::vector<Vec3>& anchors) const {
  real v = 0;
  for (std::size_t k = 1; k < keyframes.size(); ++k) {
    const real dt = keyframes[k].t - keyframes[k - 1].t;
    for (const Vec3& a : anchors)
      v = std::max(v, norm(keyframes[k].pose.apply(a) - keyframes[k - 1].pose.apply(a)) / dt);
  }
  return v;
}

}  // namespace dentsph
