#include "haptics/free_path.hpp"

#include <algorithm>
#include <cmath>

namespace dentsph::haptics {

real free_share(const State& s, const Pose& from, const Pose& to, real reach, std::vector<std::uint32_t>& tools) {
  const real reach2 = reach * reach;
  // The box the tool particles sweep, grown by the reach.
  Vec3 lo{1e30, 1e30, 1e30}, hi = -lo;
  tools.clear();
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    if (s.role[i] != Role::tool) continue;
    const Vec3 a = from.apply(s.anchor[i]), b = to.apply(s.anchor[i]);
    lo = vmin(lo, vmin(a, b));
    hi = vmax(hi, vmax(a, b));
    tools.push_back(i);
  }
  if (tools.empty()) return 1;
  const Vec3 pad{reach, reach, reach};
  lo = lo - pad;
  hi = hi + pad;
  real share = 1;
  for (std::uint32_t j = 0; j < s.size(); ++j) {
    if (s.role[j] == Role::tool) continue;  // paste and walls alike: the tool feels both
    const Vec3& x = s.pos[j];
    if (!inside(x, lo, hi)) continue;
    for (std::uint32_t i : tools) {
      // |e + t d|^2 = reach^2 for the first t in [0, share).
      const Vec3 a = from.apply(s.anchor[i]), d = to.apply(s.anchor[i]) - a, e = a - x;
      const real c = norm2(e) - reach2;
      if (c <= 0) return 0;
      const real dd = norm2(d), ed = dot(e, d);
      if (!(dd > 0) || ed >= 0) continue;  // not moving, or moving away
      const real disc = ed * ed - dd * c;
      if (disc < 0) continue;
      const real t = (-ed - std::sqrt(disc)) / dd;
      if (t >= 0 && t < share) share = t;
    }
  }
  return share;
}

}  // namespace dentsph::haptics
