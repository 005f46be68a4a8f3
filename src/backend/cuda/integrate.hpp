// Stage 6 on the GPU, per particle (physics/integrate_law.hpp, as the CPU's integrate.cpp):
// semi-implicit Euler for material, boundary at rest, tool particles to the rigid transform of the
// new pose with the velocity that move implies. Returns the particle's part of the step's
// diagnostics (largest |a|^2 and |v|^2, non-finite count).
#pragma once

#include "backend/cuda/view.hpp"
#include "physics/integrate_law.hpp"

namespace dentsph::gpu {

DENTSPH_HD inline Vec3 apply_tool(const ToolInput& t, const Vec3& a) {
  return Vec3{t.R[0] * a.x + t.R[1] * a.y + t.R[2] * a.z, t.R[3] * a.x + t.R[4] * a.y + t.R[5] * a.z,
              t.R[6] * a.x + t.R[7] * a.y + t.R[8] * a.z} +
         t.t;
}

// The tool transform of the step's input, for physics::integrate.
struct ToolTransform {
  const ToolInput& t;
  DENTSPH_HD Vec3 operator()(const Vec3& anchor) const { return apply_tool(t, anchor); }
};

DENTSPH_HD inline StepSums integrate_body(const StepView& v, std::uint32_t i) {
  const physics::Motion m = physics::integrate(v.p.role[i], v.p.pos[i], v.p.vel[i], v.force[i], v.rho[i],
                                               v.p.anchor[i], v.gravity, v.dt, ToolTransform{*v.tool});
  StepSums s;
  if (!m.finite) {
    s.non_finite = 1;
  } else {
    s.a2max = m.a2;
    s.v2max = m.v2;
  }
  return s;
}

}  // namespace dentsph::gpu
