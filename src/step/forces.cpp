// Stage 5: force densities over the 27 neighbouring cells (pressure, viscosity) and over the
// particle's bond list (adhesion, which reaches partners up to B > h). Gravity is added in
// integration, so `force` is the internal force density the tool wrench is made of.
#include "bonds/hysteresis.hpp"
#include "step/grid.hpp"
#include "step/side.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void compute_forces(const Model& model, State& s) {
  const std::uint32_t n = s.size();
  const KernelCoeffs& k = model.kernel;
  const GridIndex& g = s.grid;
  bonds::Events ev;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (s.role[i] == Role::boundary) {  // static: its force is never used
      s.force[i] = {};
      continue;
    }
    const pair::Side si = side_of(s, i);
    bonds::break_stretched(model, s, i, ev);
    Vec3 f;
    grid::for_each_neighbour_range(model.grid, g, si.pos, grid::Visit::all, [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t j = b; j < e; ++j) {
        const Vec3 d{si.pos.x - g.x[j], si.pos.y - g.y[j], si.pos.z - g.z[j]};
        const real r2 = norm2(d);
        if (r2 >= k.h2 || j == i) continue;
        f += pair::pressure_viscosity(si, side_of(s, j), d, std::sqrt(r2), k);
        bonds::try_form(model, s, i, j, r2, ev);  // A < h: every pair to bond is here
      }
    });
    const std::uint32_t id = s.id[i];
    for (int b = 0; b < s.bonds.count(id); ++b) {
      const std::uint32_t j = s.index_of_id[s.bonds.partner(id, b)];
      const Vec3 d = si.pos - s.pos[j];
      f += pair::adhesion(si, side_of(s, j), d, norm(d), model.adhesion, k);
    }
    s.force[i] = f;
  }
  bonds::record(s, ev);
}

}  // namespace dentsph::stages
