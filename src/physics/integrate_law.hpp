// Stage 6's law for one particle (docs/model.md, "One step", step 6): semi-implicit (symplectic) Euler for
// material, a = f / rho + g, v += dt a, r += dt v; boundary particles at rest; tool particles moved
// to the rigid transform of the new tool pose with the velocity that move implies. Written once
// for the CPU step (step/integrate.cpp) and the CUDA stage body (backend/cuda/integrate.hpp); each
// passes its own transform of the tool pose (a quaternion on the CPU, a matrix on the GPU).
#pragma once

#include <cmath>

#include "dentsph/config.hpp"
#include "dentsph/state.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph::physics {

// What integrating one particle tells the step's diagnostics: its squared acceleration and speed,
// and whether it stayed finite (material only; zero and finite for the others).
struct Motion {
  real a2 = 0, v2 = 0;
  bool finite = true;
};

// The Motion of a material particle that moved to `pos` with velocity `vel` and acceleration
// `accel` over the step: written once for this integration and the iisph solver's
// (solver/finish.cpp, whose velocity comes from its solve).
DENTSPH_HD inline Motion motion_of(const Vec3& accel, const Vec3& vel, const Vec3& pos) {
  Motion m;
  m.a2 = norm2(accel);
  m.v2 = norm2(vel);
  m.finite = std::isfinite(m.a2) && std::isfinite(m.v2) && is_finite(pos);
  return m;
}

// A particle's Motion into the step's diagnostics: the largest squares of the finite ones, and the
// count of the others.
template <class Count>
DENTSPH_HD inline void tally(const Motion& m, real& a2max, real& v2max, Count& non_finite) {
  if (!m.finite) {
    ++non_finite;
  } else {
    a2max = a2max < m.a2 ? m.a2 : a2max;
    v2max = v2max < m.v2 ? m.v2 : v2max;
  }
}

// One particle of `role` over dt: `force` is its force density (N/m^3), `anchor` its place in the
// tool frame and `tool(anchor)` where the new tool pose puts it.
template <class ToolTransform>
DENTSPH_HD inline Motion integrate(Role role, Vec3& pos, Vec3& vel, const Vec3& force, real rho, const Vec3& anchor,
                                   const Vec3& gravity, real dt, const ToolTransform& tool) {
  Motion m;
  switch (role) {
    case Role::material: {
      const Vec3 a = force / rho + gravity;
      const Vec3 v = vel + a * dt;
      const Vec3 p = pos + v * dt;
      vel = v;
      pos = p;
      m = motion_of(a, v, p);
      break;
    }
    case Role::boundary:
      vel = {};
      break;
    case Role::tool: {
      const Vec3 p = tool(anchor);
      vel = (p - pos) / dt;
      pos = p;
      break;
    }
  }
  return m;
}

}  // namespace dentsph::physics
