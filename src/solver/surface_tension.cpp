// Surface tension and wetting (docs/model.md, "Surface tension and wetting"): the paste's cohesion
// and curvature forces and its adhesion to walls, Akinci, Akinci & Teschner 2013, added to v* after
// advect() and before the pressure solve. Explicit: each material row's force from its neighbours'
// positions and normals, summed in the row's order (every thread count gives the same bits).
#include <cmath>

#include "physics/kernels.hpp"
#include "solver/iisph.hpp"

namespace dentsph::iisph {

void surface_tension(const Model& model, State& s, IisphScratch& x, int threads) {
  const real sigma = model.iisph.surface_tension;
  if (!(sigma > 0)) return;
  const real h = model.kernel.h, dt = model.dt;
  const real scale = kSurfaceTensionScale * sigma / (h * h);  // gamma_ij = scale / (rho0_i rho0_j)
  const real wetting = model.iisph.wetting;
  const real cohesion_scale = kernels::cohesion_scale(h), adhesion_scale = kernels::wall_adhesion_scale(h);
  const std::int64_t n = s.size();
  // Each material particle's normal n_i = h sum_j V_j gradW_ij over its material neighbours: the
  // paste's colour field's gradient, 0 inside, about 1 / (the kernel's reach) across its surface.
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t k = 0; k < n; ++k) {
    const std::uint32_t i = std::uint32_t(k);
    Vec3 nn;
    if (s.role[i] == Role::material) {
      const SolverPair* row = x.pairs.data() + std::size_t(i) * IisphScratch::kPairStride;
      for (std::uint32_t q = 0; q < x.n_material[i]; ++q) nn += row[q].grad() * x.inv_rho[row[q].j];
    }
    x.normal[i] = nn * h;
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t k = 0; k < n; ++k) {
    const std::uint32_t i = std::uint32_t(k);
    if (s.role[i] != Role::material) continue;
    const SolverPair* row = x.pairs.data() + std::size_t(i) * IisphScratch::kPairStride;
    const real mi = s.mass[i], rho_i = 1 / x.inv_rho[i];
    Vec3 f;
    for (std::uint32_t q = 0; q < x.n_material[i]; ++q) {
      const std::uint32_t j = row[q].j;
      const Vec3 d = s.pos[i] - s.pos[j];
      const real r = norm(d);
      const real gamma = scale / (s.rho0[i] * s.rho0[j]);
      // Akinci's correction K_ij = 2 rho0 / (rho_i + rho_j): stronger where the paste is thin.
      const real K = (s.rho0[i] + s.rho0[j]) / (rho_i + 1 / x.inv_rho[j]);
      Vec3 fij = (x.normal[i] - x.normal[j]) * (-gamma * mi);
      if (r > 0) fij += d * (-gamma * mi * s.mass[j] * cohesion_scale * kernels::cohesion(r, h) / r);
      f += fij * K;
    }
    if (wetting > 0) {
      const real beta = wetting * scale / (s.rho0[i] * s.rho0[i]);
      for (std::uint32_t q = IisphScratch::kPairStride - x.n_other[i]; q < IisphScratch::kPairStride; ++q) {
        const std::uint32_t j = row[q].j;
        if (s.role[j] != Role::boundary) continue;  // a wall (the tooth, set paste), not the instrument
        const Vec3 d = s.pos[i] - s.pos[j];
        const real r = norm(d);
        if (!(r > 0)) continue;
        // Psi_j = rho0_i V_j: the wall particle's volume filled with the paste.
        const real psi = s.rho0[i] * s.mass[j] * x.inv_rho[j];
        f += d * (-beta * mi * psi * adhesion_scale * kernels::wall_adhesion(r, h) / r);
      }
    }
    const Vec3 dv = f * (dt / mi);
    x.v_star[i] += dv;
    x.v_a[i] += dv;
  }
}

}  // namespace dentsph::iisph
