// The all-pairs reference (the paper's "less efficient algorithm", section 3.2): every pair is
// visited, nothing is sorted. Kept as the truth the grid step (and every faster backend) is
// tested against; it shares the pair terms, pressure, integration and tool wrench.
#include "dentsph/step.hpp"
#include "physics/kernels.hpp"
#include "step/pressure_stage.hpp"
#include "step/side.hpp"
#include "step/stages.hpp"

namespace dentsph {

namespace stages {

void compute_density_all_pairs(const Model& model, State& s) {
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    real rho = 0;
    for (std::uint32_t j = 0; j < n; ++j) rho += s.mass[j] * kernels::poly6(norm2(s.pos[i] - s.pos[j]), model.kernel);
    s.rho[i] = rho;
  }
}

// Stage 4, a pass of its own: P = max(0, Kp (rho - rho0)) and m / rho of every particle.
void compute_pressure_all_pairs(State& s) {
  for (std::uint32_t i = 0; i < s.size(); ++i) pressure_of(s, i);
}

void compute_forces_all_pairs(const Model& model, State& s) {
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    if (s.role[i] == Role::boundary) {  // static: its force is never used
      s.force[i] = {};
      continue;
    }
    const pair::Side si = pair::side_of(s, i);
    Vec3 f;
    for (std::uint32_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const Vec3 d = si.pos - s.pos[j];
      const real r = norm(d);
      const pair::Side sj = pair::side_of(s, j);
      f += pair::pressure_viscosity(si, sj, d, r, model.kernel);
      if (s.bonds.has(s.id[i], s.id[j])) f += pair::adhesion(si, sj, d, r, model.adhesion, model.kernel);
    }
    s.force[i] = f;
  }
}

}  // namespace stages

void step_all_pairs(const Model& model, State& state) {
  stages::update_bonds_all_pairs(model, state);
  stages::compute_density_all_pairs(model, state);
  stages::compute_pressure_all_pairs(state);
  stages::compute_forces_all_pairs(model, state);
  stages::compute_tool_wrench(state);
  stages::integrate(model, state, 1);
}

}  // namespace dentsph
