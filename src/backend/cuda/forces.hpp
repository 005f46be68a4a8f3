// Stage 5 on the GPU, per sorted particle (the CPU's forces.cpp): the adhesion of the bonded
// partners (breaking the bonds stretched past B), then pressure and viscosity of the neighbours
// within h, forming the bonds closer than A on the way. Boundary particles are static: force 0.
#pragma once

#include "backend/cuda/bond_slots.hpp"
#include "backend/cuda/neighbourhood.hpp"
#include "physics/pair_terms.hpp"

namespace dentsph::gpu {

// The view's arrays that a pair::Side gathers, under the names a State gives them.
struct SideArrays {
  const Vec3 *pos, *vel;
  const real *volume, *pressure, *mu, *Ka;
};

DENTSPH_HD inline pair::Side side_of(const StepView& v, std::uint32_t i) {
  return pair::side_of(SideArrays{v.p.pos, v.p.vel, v.volume, v.pressure, v.p.mu, v.p.Ka}, i);
}

DENTSPH_HD inline void forces_body(const StepView& v, std::uint32_t i, BondEvents& ev) {
  if (v.p.role[i] == Role::boundary) {
    v.force[i] = {};
    return;
  }
  const pair::Side si = side_of(v, i);
  const bond_rules::Thresholds t = bond_rules::thresholds(v.adhesion);
  const std::uint32_t id = v.p.id[i];
  Vec3 f;
  // Bonds first: break those stretched past B, add the adhesion of the rest. Bonds formed below
  // (r < A) add nothing this step: W_adh is zero below A.
  for (int b = int(v.bond_count[id]) - 1; b >= 0; --b) {
    const std::uint32_t j = v.index_of_id[v.bond_partner[std::size_t(id) * v.bond_capacity + b]];
    const Vec3 d = si.pos - v.p.pos[j];
    const real r2 = norm2(d);
    if (bond_rules::stretched(r2, t)) {
      count_break(v, i, j, ev);
      remove_bond(v, id, std::uint32_t(b));
    } else {
      f += pair::adhesion(si, side_of(v, j), d, std::sqrt(r2), v.adhesion, v.kernel);
    }
  }
  const real h2 = v.kernel.h2;
  for_each_neighbour(v, si.pos, grid::Visit::all, [&](std::uint32_t j) {
    const Vec3 d = si.pos - v.p.pos[j];
    const real r2 = norm2(d);
    if (j == i || r2 >= h2) return;
    f += pair::pressure_viscosity(si, side_of(v, j), d, std::sqrt(r2), v.kernel);
    try_form(v, i, j, r2, t, ev);  // A < h: every pair to bond is here
  });
  v.force[i] = f;
}

}  // namespace dentsph::gpu
