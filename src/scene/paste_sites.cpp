#include "scene/paste_sites.hpp"

#include <algorithm>
#include <cmath>

namespace dentsph::scene {

std::vector<PasteSite> paste_sites(const PreparedTooth& tooth, real s) {
  const ToothFrame& fr = tooth.frame();
  const Bounds b = tooth.cavity_bounds();
  real reach = 0;
  for (const Vec3& c : {b.min, b.max}) {
    const Vec3 l = fr.to_local(c);
    reach = std::max({reach, std::abs(l.x), std::abs(l.y), std::abs(l.z)});
  }
  const int n = int(std::ceil(reach / s)) + 2;
  std::vector<PasteSite> sites;
  for (int k = -n; k <= n; ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        const Vec3 local{i * s, j * s, (k + 0.5) * s};
        const Vec3 w = fr.to_world(local);
        if (tooth.cavity_distance(w).distance > -0.5 * s || tooth.distance(w).distance < 0.5 * s) continue;
        PasteSite site{local, tooth.in_cavity(w), false};
        if (!site.in_cavity) {
          if (local.z <= 0) continue;
          site.over_cavity = tooth.in_cavity(fr.to_world({local.x, local.y, -0.5 * s}));
        }
        sites.push_back(site);
      }
  return sites;
}

}  // namespace dentsph::scene
