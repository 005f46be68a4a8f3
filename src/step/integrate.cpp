// Stage 6 over the particles (the law of one particle: physics/integrate_law.hpp): semi-implicit
// (symplectic) Euler for material particles, a = f / rho + g, v += dt a, r += dt v (docs/model.md, "One step").
// Boundary particles stay; tool particles take the rigid transform of the new tool pose, with the
// velocity that move implies. The step's diagnostics and clock.
#include <algorithm>
#include <cmath>

#include "physics/integrate_law.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void integrate(const Model& model, State& s, int threads) {
  const real dt = model.dt;
  real a2max = 0, v2max = 0;
  std::uint64_t non_finite = 0;
  const std::int64_t n = s.size();
  const auto tool = [&s](const Vec3& anchor) { return s.tool_pose.apply(anchor); };
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : a2max, v2max) reduction(+ : non_finite)
  for (std::int64_t i = 0; i < n; ++i) {
    const physics::Motion m = physics::integrate(s.role[i], s.pos[i], s.vel[i], s.force[i], s.rho[i], s.anchor[i],
                                                 model.gravity, dt, tool);
    physics::tally(m, a2max, v2max, non_finite);
  }
  close_step(s, a2max, v2max, non_finite, dt);
}

void close_step(State& s, real a2max, real v2max, std::uint64_t non_finite, real dt) {
  s.diagnostics.max_accel = std::sqrt(a2max);
  s.diagnostics.max_speed = std::sqrt(v2max);
  s.diagnostics.non_finite = non_finite;
  s.tool_pose_applied = s.tool_pose;
  s.time += dt;
  ++s.steps;
}

}  // namespace dentsph::stages
