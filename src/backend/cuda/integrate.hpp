// Stage 6 on the GPU, per particle (the CPU's integrate.cpp): semi-implicit Euler for material,
// boundary at rest, tool particles to the rigid transform of the new pose with the velocity that
// move implies. Returns the particle's part of the step's diagnostics (largest |a|^2 and |v|^2,
// non-finite count).
#pragma once

#include <cmath>

#include "backend/cuda/view.hpp"

namespace dentsph::gpu {

DENTSPH_HD inline Vec3 apply_tool(const ToolInput& t, const Vec3& a) {
  return Vec3{t.R[0] * a.x + t.R[1] * a.y + t.R[2] * a.z, t.R[3] * a.x + t.R[4] * a.y + t.R[5] * a.z,
              t.R[6] * a.x + t.R[7] * a.y + t.R[8] * a.z} +
         t.t;
}

DENTSPH_HD inline StepSums integrate_body(const StepView& v, std::uint32_t i) {
  StepSums s;
  const real dt = v.dt;
  switch (v.p.role[i]) {
    case Role::material: {
      const Vec3 a = v.force[i] / v.rho[i] + v.gravity;
      const Vec3 vel = v.p.vel[i] + a * dt;
      const Vec3 pos = v.p.pos[i] + vel * dt;
      v.p.vel[i] = vel;
      v.p.pos[i] = pos;
      const real a2 = norm2(a), v2 = norm2(vel);
      if (!std::isfinite(a2) || !std::isfinite(v2) || !is_finite(pos)) {
        s.non_finite = 1;
      } else {
        s.a2max = a2;
        s.v2max = v2;
      }
      break;
    }
    case Role::boundary:
      v.p.vel[i] = {};
      break;
    case Role::tool: {
      const Vec3 p = apply_tool(*v.tool, v.p.anchor[i]);
      v.p.vel[i] = (p - v.p.pos[i]) / dt;
      v.p.pos[i] = p;
      break;
    }
  }
  return s;
}

}  // namespace dentsph::gpu
