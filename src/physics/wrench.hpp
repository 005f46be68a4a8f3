// One tool particle's part of the wrench on the tool (MODEL.md, "Haptic force"): its m a = f V
// (f the force density, V = m / rho; gravity left out) and that force's moment about the tool's
// origin. Written once for the CPU step (step/tool_wrench.cpp) and the CUDA stage body
// (backend/cuda/tool_wrench.hpp); each sums the terms in its own fixed order.
#pragma once

#include "dentsph/config.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph::physics {

struct WrenchTerm {
  Vec3 force;   // N
  Vec3 torque;  // N m
};

// Nothing where the density is not positive (a particle the density pass has not reached).
DENTSPH_HD inline WrenchTerm tool_wrench_term(const Vec3& force_density, real mass, real rho, const Vec3& pos,
                                              const Vec3& origin) {
  WrenchTerm w;
  if (!(rho > 0)) return w;
  w.force = force_density * (mass / rho);
  w.torque = cross(pos - origin, w.force);
  return w;
}

}  // namespace dentsph::physics
