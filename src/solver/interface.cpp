// The iisph solver's paste-instrument interface (docs/model.md, "Tack"). The viscosity solve couples
// a paste particle to the instrument particles within h with no slip, which holds the paste to the
// instrument whatever the tension. Where the materials give their contact a strength sigma
// (Material::interface_strength), the contact is rigid-plastic in tension: after the solve, a paste
// particle whose pull towards the instrument (the viscous force of its instrument pairs, along their
// mean line n towards the instrument) is over sigma V_i^(2/3) (its share of the interface) is held
// by sigma V_i^(2/3) n alone: its instrument pairs leave the coupling, that force goes into its
// velocity (v* += dt F / m), its reaction onto the instrument (finish.cpp), and the solve runs
// again. A particle drawn away from the instrument so keeps that pull until it is clear of it (no
// instrument particle within h): a cohesive zone h - s wide, whose work per area is about sigma s.
// Nothing is remembered from step to step; pressure still pushes.
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/iisph.hpp"

namespace dentsph::iisph {

std::uint32_t cap_tool_pull(const Model& model, State& s, IisphScratch& x, int threads) {
  constexpr std::size_t stride = IisphScratch::kPairStride;
  const std::int64_t nm = std::int64_t(x.material.size());
  const real dt = model.dt;
  std::uint32_t capped = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : capped)
  for (std::int64_t m = 0; m < nm; ++m) {
    const std::uint32_t i = x.material[m];
    x.capped[i] = 0;
    SolverPair* row = x.pairs.data() + std::size_t(i) * stride;
    const std::size_t first = stride - x.n_other[i];
    const Material& paste = model.materials[s.material[i] & kMaterialMask];
    real strength = std::numeric_limits<real>::infinity();
    Vec3 line, force;  // the mean direction to the instrument's pairs, their viscous force on i
    const real vol = s.mass[i] * x.inv_rho[i];
    const Vec3 vi = x.v_a[i];
    for (std::size_t q = first; q < stride; ++q) {
      const std::uint32_t j = row[q].j;
      if (s.role[j] != Role::tool) continue;
      const real c = contact_strength(paste.interface_strength,
                                      model.materials[s.material[j] & kMaterialMask].interface_strength);
      if (c > 0) strength = std::min(strength, c);
      const Vec3 d = s.pos[j] - s.pos[i];
      const real r = norm(d);
      if (r > 0) line += d / r;
      if (x.rheology) {
        const Vec3 g = row[q].grad();
        force += g * (-vol * row[q].visc * dot(vi - s.vel[j], g));  // the projected form (rheology.cpp)
      } else {
        force += (s.vel[j] - vi) * (vol * row[q].visc);
      }
    }
    const real len = norm(line);
    if (!std::isfinite(strength) || !(len > 0)) continue;
    const Vec3 n = line / len;
    const real hold = strength * std::cbrt(vol * vol);
    if (!(dot(force, n) > hold)) continue;
    // Held by the strength alone: the instrument pairs leave the coupling (the row's diagonal and
    // fixed terms without them) and the strength's pull goes into v*.
    x.capped[i] = 1;
    ++capped;
    x.interface_force[i] = n * hold;
    x.v_star[i] += n * (hold * dt / s.mass[i]);
    for (std::size_t q = first; q < stride; ++q) {
      const std::uint32_t j = row[q].j;
      if (s.role[j] != Role::tool) continue;
      const real c = row[q].visc;
      if (x.rheology) {
        const Vec3 g = row[q].grad();
        x.visc_block[i] -= Vec3{g.x * g.x, g.y * g.y, g.z * g.z} * c;
        x.visc_fixed[i] -= g * (c * dot(s.vel[j], g));
      } else {
        x.visc_diag[i] -= c;
        x.visc_fixed[i] -= s.vel[j] * c;
      }
      row[q].visc = 0;
    }
  }
  x.capped_count = capped;
  return capped;
}

}  // namespace dentsph::iisph
