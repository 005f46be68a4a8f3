// The iisph solver's bookkeeping: the material particles in cell order, listed after each rebuild
// (their order changes only there); the particles the solve does not move (the tool's velocity
// over the step: it is kinematic, so the pressure solve and the viscosity take it as given; the
// boundary at rest) and their entries in the solver's per-particle arrays; and, once the pair pass
// has found who neighbours whom, the rows of this step's pressure solve.
#include "solver/iisph.hpp"

namespace dentsph::iisph {

void list_material(const State& s, IisphScratch& x) {
  // Paste that set (the cure's gel transition) became wall, so there can be fewer material particles
  // than the lists were sized for (IisphScratch::resize, after particles were added): cleared and
  // refilled within their capacity, no allocation.
  x.material.clear();
  x.tools.clear();
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    if (s.role[i] == Role::material) x.material.push_back(i);
    if (s.role[i] == Role::tool) x.tools.push_back(i);
  }
}

void prepare_particles(const Model& model, State& s, IisphScratch& x, int threads) {
  const std::int64_t n = s.size();
  const real inv_dt = 1 / model.dt;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    if (s.role[i] == Role::material) continue;
    s.vel[i] = s.role[i] == Role::tool ? (s.tool_pose.apply(s.anchor[i]) - s.pos[i]) * inv_dt : Vec3{};
    x.accel[i] = {};
    x.v_a[i] = s.vel[i];
  }
}

void list_active_rows(State& s, IisphScratch& x) {
  std::uint32_t k = 0;
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    if (s.role[i] == Role::material || x.n_material[i] > 0) {
      x.active[k++] = i;
    } else {  // no material within h: nothing to push, no pressure
      s.pressure[i] = 0;
      x.q[i] = 0;
    }
  }
  x.active_count = k;
}

}  // namespace dentsph::iisph
