// Stage 3 on the GPU, per sorted particle: rho_i = sum_j m_j W_poly6(r_ij) over all roles, self
// included (the CPU's density.cpp). A boundary particle adds its moving neighbours to the static
// boundary part (rho_static), which static_density_body computes once after an upload.
#pragma once

#include "backend/cuda/neighbourhood.hpp"
#include "physics/kernels.hpp"

namespace dentsph::gpu {

// poly6 * sum of m_j (h^2 - r^2)^3 over the neighbours of i of the kind `visit` asks for.
DENTSPH_HD inline real density_sum(const StepView& v, std::uint32_t i, grid::Visit visit) {
  const Vec3 pi = v.p.pos[i];
  const real h2 = v.kernel.h2;
  real sum = 0;
  for_each_neighbour(v, pi, visit, [&](std::uint32_t j) {
    const real w = h2 - norm2(pi - v.p.pos[j]);
    if (w > 0) sum += kernels::poly6_mass_term(v.p.mass[j], w);
  });
  return v.kernel.poly6 * sum;
}

DENTSPH_HD inline void static_density_body(const StepView& v, std::uint32_t i) {
  const bool boundary = v.p.role[i] == Role::boundary;
  v.rho_static[v.p.id[i]] = boundary ? density_sum(v, i, grid::Visit::boundary) : 0;
}

DENTSPH_HD inline void density_body(const StepView& v, std::uint32_t i) {
  if (v.p.role[i] == Role::boundary)
    v.rho[i] = v.rho_static[v.p.id[i]] + density_sum(v, i, grid::Visit::moving);
  else
    v.rho[i] = density_sum(v, i, grid::Visit::all);
}

}  // namespace dentsph::gpu
