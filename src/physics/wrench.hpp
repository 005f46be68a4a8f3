// One tool particle's part of the wrench on the tool (docs/model.md, "Haptic force"): its m a = f V
// (f the force density, V = m / rho; gravity left out) and that force's moment about the tool's
// origin. Written once for the paper's CPU step (step/tool_wrench.cpp), the CUDA stage body
// (backend/cuda/tool_wrench.hpp) and the iisph solver (solver/finish.cpp, which has the force
// itself); each sums the terms in its own fixed order.
#pragma once

#include "dentsph/config.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph::physics {

struct WrenchTerm {
  Vec3 force;   // N
  Vec3 torque;  // N m
};

// A force (N) on a tool particle at `pos` and its moment about the tool's origin.
DENTSPH_HD inline WrenchTerm wrench_of(const Vec3& force, const Vec3& pos, const Vec3& origin) {
  WrenchTerm w;
  w.force = force;
  w.torque = cross(pos - origin, force);
  return w;
}

// From the particle's force density; nothing where the density is not positive (a particle the
// density pass has not reached).
DENTSPH_HD inline WrenchTerm tool_wrench_term(const Vec3& force_density, real mass, real rho, const Vec3& pos,
                                              const Vec3& origin) {
  if (!(rho > 0)) return WrenchTerm{};
  return wrench_of(force_density * (mass / rho), pos, origin);
}

}  // namespace dentsph::physics
