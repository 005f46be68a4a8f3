// The iisph solver's explicit part: the adhesion of bonded pairs (the paper's kernel, eq. 11, the
// force on i being (Ka_i + Ka_j)/2 V_i V_j W_adh(r) rhat with V = m / rho) and gravity give each
// material particle its velocity v* = v + dt (g + f_adh / m); bonds stretched past B break first
// (the paper's hysteresis, bonds/hysteresis.hpp). A tool row keeps its adhesion force for the wrench.
// The same pass completes each row's viscosity weights with 1 / rho_j (known for every particle only
// now) and the terms of the boundary and tool neighbours, whose velocities are fixed for the step.
#include <cmath>

#include "bonds/hysteresis.hpp"
#include "physics/kernels.hpp"
#include "solver/iisph.hpp"

namespace dentsph::iisph {

namespace {

// Adhesion force (N) on moving particle i from its bonded partners; breaks those past B.
Vec3 bonded_adhesion(const Model& model, State& s, const IisphScratch& x, std::uint32_t i, bonds::Events& ev) {
  const real B2 = model.adhesion.B * model.adhesion.B;
  const std::uint32_t id = s.id[i];
  const real vi = s.mass[i] * x.inv_rho[i];
  Vec3 f;
  for (int b = s.bonds.count(id) - 1; b >= 0; --b) {
    const std::uint32_t j = s.index_of_id[s.bonds.partner(id, b)];
    const Vec3 d = s.pos[i] - s.pos[j];
    const real r2 = norm2(d);
    if (r2 > B2) {
      bonds::count_break(s, i, j, ev);
      s.bonds.remove_at(id, b);
      continue;
    }
    const real r = std::sqrt(r2);
    const real w = r > 0 ? kernels::adhesion(r, model.adhesion, model.kernel) : 0;
    f += d * (0.5 * (s.Ka[i] + s.Ka[j]) * vi * s.mass[j] * x.inv_rho[j] * w / r);
  }
  return f;
}

}  // namespace

void advect(const Model& model, State& s, IisphScratch& x, int threads) {
  const std::int64_t n = s.size();
  const real dt = model.dt;
  std::uint64_t broken = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : broken)
  for (std::int64_t k = 0; k < n; ++k) {
    const std::uint32_t i = std::uint32_t(k);
    if (s.role[i] == Role::boundary) continue;
    bonds::Events ev;
    const Vec3 f = bonded_adhesion(model, s, x, i, ev);
    broken += ev.broken;
    SolverPair* row = x.pairs.data() + std::size_t(i) * IisphScratch::kPairStride;
    real diag = 0;
    for (std::uint32_t q = 0; q < x.n_material[i]; ++q) {
      row[q].visc = float(row[q].visc * x.inv_rho[row[q].j]);
      diag += row[q].visc;
    }
    if (s.role[i] == Role::tool) {
      x.tool_force[i] = f;
      continue;
    }
    Vec3 visc_fixed;
    real div_fixed = 0;
    for (std::uint32_t q = IisphScratch::kPairStride - x.n_other[i]; q < IisphScratch::kPairStride; ++q) {
      const std::uint32_t j = row[q].j;
      row[q].visc = float(row[q].visc * x.inv_rho[j]);
      diag += row[q].visc;
      visc_fixed += s.vel[j] * row[q].visc;
      div_fixed += dot(s.vel[j], row[q].grad());
    }
    x.visc_diag[i] = diag;
    x.visc_fixed[i] = visc_fixed;
    x.div_fixed[i] = div_fixed;
    const Vec3 v = s.vel[i] + (model.gravity + f / s.mass[i]) * dt;
    x.v_star[i] = v;
    x.v_a[i] = v;
  }
  bonds::Events total;
  total.broken = broken;
  bonds::record(s, total);
}

}  // namespace dentsph::iisph
