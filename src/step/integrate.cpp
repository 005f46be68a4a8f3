// Stage 6: semi-implicit (symplectic) Euler for material particles, a = f / rho + g,
// v += dt a, r += dt v (MODEL.md). Boundary particles stay; tool particles take the rigid
// transform of the new tool pose, with the velocity that move implies.
#include <algorithm>
#include <cmath>

#include "step/stages.hpp"

namespace dentsph::stages {

void integrate(const Model& model, State& s, int threads) {
  const real dt = model.dt;
  real a2max = 0, v2max = 0;
  std::uint64_t non_finite = 0;
  const std::int64_t n = s.size();
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : a2max, v2max) reduction(+ : non_finite)
  for (std::int64_t i = 0; i < n; ++i) {
    switch (s.role[i]) {
      case Role::material: {
        const Vec3 a = s.force[i] / s.rho[i] + model.gravity;
        s.vel[i] += a * dt;
        s.pos[i] += s.vel[i] * dt;
        const real a2 = norm2(a), v2 = norm2(s.vel[i]);
        if (!std::isfinite(a2) || !std::isfinite(v2) || !is_finite(s.pos[i])) {
          ++non_finite;
        } else {
          a2max = std::max(a2max, a2);
          v2max = std::max(v2max, v2);
        }
        break;
      }
      case Role::boundary:
        s.vel[i] = {};
        break;
      case Role::tool: {
        const Vec3 p = s.tool_pose.apply(s.anchor[i]);
        s.vel[i] = (p - s.pos[i]) / dt;
        s.pos[i] = p;
        break;
      }
    }
  }
  s.diagnostics.max_accel = std::sqrt(a2max);
  s.diagnostics.max_speed = std::sqrt(v2max);
  s.diagnostics.non_finite = non_finite;
  s.tool_pose_applied = s.tool_pose;
  s.time += dt;
  ++s.steps;
}

}  // namespace dentsph::stages
