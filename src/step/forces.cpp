// Stage 5: force densities over the 27 neighbouring cells (pressure, viscosity) and over the
// particle's bond list (adhesion, which reaches partners up to B > h). Gravity is added in
// integration, so `force` is the internal force density the tool wrench is made of.
#include "step/grid.hpp"
#include "step/side.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void compute_forces(const Model& model, State& s) {
  const std::uint32_t n = s.size();
  const KernelCoeffs& k = model.kernel;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (s.role[i] == Role::boundary) {  // static: its force is never used
      s.force[i] = {};
      continue;
    }
    const pair::Side si = side_of(s, i);
    Vec3 f;
    grid::for_each_in_neighbourhood(model.grid, s.grid, si.pos, [&](std::uint32_t j) {
      if (j == i) return;
      const Vec3 d = si.pos - s.pos[j];
      const real r2 = norm2(d);
      if (r2 >= k.h2) return;
      f += pair::pressure_viscosity(si, side_of(s, j), d, std::sqrt(r2), k);
    });
    const std::uint32_t id = s.id[i];
    for (int b = 0; b < s.bonds.count(id); ++b) {
      const std::uint32_t j = s.index_of_id[s.bonds.partner(id, b)];
      const Vec3 d = si.pos - s.pos[j];
      f += pair::adhesion(si, side_of(s, j), d, norm(d), model.adhesion, k);
    }
    s.force[i] = f;
  }
}

}  // namespace dentsph::stages
