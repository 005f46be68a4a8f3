// Stage 6: semi-implicit (symplectic) Euler for material particles, a = f / rho + g,
// v += dt a, r += dt v (MODEL.md). Boundary particles stay; tool particles take the rigid
// transform of the new tool pose, with the velocity that move implies.
#include <algorithm>
#include <cmath>

#include "step/stages.hpp"

namespace dentsph::stages {

void integrate(const Model& model, State& s) {
  const real dt = model.dt;
  StepDiagnostics diag;
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    switch (s.role[i]) {
      case Role::material: {
        const Vec3 a = s.force[i] / s.rho[i] + model.gravity;
        s.vel[i] += a * dt;
        s.pos[i] += s.vel[i] * dt;
        const real a2 = norm2(a), v2 = norm2(s.vel[i]);
        if (!std::isfinite(a2) || !std::isfinite(v2) || !is_finite(s.pos[i])) {
          ++diag.non_finite;
        } else {
          diag.max_accel = std::max(diag.max_accel, a2);
          diag.max_speed = std::max(diag.max_speed, v2);
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
  diag.max_accel = std::sqrt(diag.max_accel);
  diag.max_speed = std::sqrt(diag.max_speed);
  s.diagnostics = diag;
  s.tool_pose_applied = s.tool_pose;
  s.time += dt;
  ++s.steps;
}

}  // namespace dentsph::stages
