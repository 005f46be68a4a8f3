// The end of an iisph step: the force on the tool (the reaction of the pressure, viscous and
// adhesion forces its particles exert on material), then each material particle's velocity
// v = v** + dt a_p and position r += dt v (kept out of the walls, model.walls), the tool moved to
// its pose (material that would leave the domain held where it is, with Model::hold_outside_domain),
// and the outputs: `pressure` is the solve's (mechanical) pressure, `force` the internal
// force density of material, the diagnostics of the paper's step (largest acceleration and speed,
// non-finite material, wall projections).
#include <algorithm>
#include <cmath>

#include "physics/integrate_law.hpp"
#include "physics/wrench.hpp"
#include "solver/iisph.hpp"
#include "solver/pressure_terms.hpp"
#include "step/stages.hpp"

namespace dentsph::iisph {

namespace {

// Force (N) on tool particle i from its material neighbours (pressure, viscosity) and its bonds.
Vec3 tool_particle_force(const State& s, const IisphScratch& x, std::uint32_t i) {
  const SolverPair* row = x.pairs.data() + std::size_t(i) * IisphScratch::kPairStride;
  Vec3 pressure, viscous;
  for (std::uint32_t e = 0; e < x.n_material[i]; ++e) {
    const std::uint32_t j = row[e].j;
    pressure += row[e].grad() * pair_q(x, i, j);
    // The coupling its contact's strength weakened (interface.cpp).
    const real c = s.diagnostics.interface_capped > 0 ? row[e].visc * x.interface_scale[j] : row[e].visc;
    if (x.rheology) {  // the projected form (rheology.cpp)
      const Vec3 g = row[e].grad();
      viscous += g * (c * dot(x.v_a[j] - s.vel[i], g));
    } else {
      viscous += (x.v_a[j] - s.vel[i]) * c;  // v** of material, the tool's own velocity
    }
  }
  return pressure * -s.mass[i] + viscous * (s.mass[i] * x.inv_rho[i]) + x.tool_force[i];
}

void tool_wrench(State& s, const IisphScratch& x) {
  ToolWrench w;
  const Vec3 c = s.tool_pose_applied.position;
  for (const std::uint32_t i : x.tools) {  // the tool particles in index order (rows.cpp)
    const physics::WrenchTerm t = physics::wrench_of(tool_particle_force(s, x, i), s.pos[i], c);
    s.force[i] = t.force * (s.rho[i] / s.mass[i]);  // force density, as the paper's step keeps it
    w.force += t.force;
    w.torque += t.torque;
  }
  s.tool_wrench = w;
}

}  // namespace

void finish(const Model& model, State& s, const IisphScratch& x, int threads) {
  tool_wrench(s, x);
  const real dt = model.dt;
  real a2max = 0, v2max = 0;
  std::uint64_t non_finite = 0, projected = 0, held = 0;
  const WallField* walls = model.walls.get();
  const bool hold = model.hold_outside_domain;
  const std::int64_t n = s.size();
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : a2max, v2max) reduction(+ : non_finite, projected, held)
  for (std::int64_t i = 0; i < n; ++i) {
    switch (s.role[i]) {
      case Role::material: {
        Vec3 v = x.v_a[i];
        Vec3 r = s.pos[i] + v * dt;
        if (walls && walls->project(r, v)) ++projected;  // kept out of the walls (wall_field.hpp)
        if (hold && !inside(r, model.domain_min, model.domain_max)) {
          // Off the model (Model::hold_outside_domain): held where it is, at rest, out of the
          // step's figures.
          s.force[i] = {};
          s.vel[i] = {};
          s.volume[i] = s.mass[i] / s.rho[i];
          ++held;
          break;
        }
        const Vec3 a = (v - s.vel[i]) / dt;
        s.force[i] = (a - model.gravity) * s.rho[i];
        s.vel[i] = v;
        s.pos[i] = r;
        s.volume[i] = s.mass[i] / s.rho[i];
        physics::tally(physics::motion_of(a, v, r), a2max, v2max, non_finite);
        break;
      }
      case Role::boundary:
        s.volume[i] = s.mass[i] / s.rho[i];
        s.force[i] = {};
        break;
      case Role::tool:
        s.pos[i] = s.tool_pose.apply(s.anchor[i]);
        s.volume[i] = s.mass[i] / s.rho[i];
        break;
    }
  }
  stages::close_step(s, a2max, v2max, non_finite, dt);
  s.diagnostics.wall_projections = projected;
  s.diagnostics.held = held;
}

}  // namespace dentsph::iisph
