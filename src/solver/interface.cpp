// The iisph solver's paste-instrument interface (docs/model.md, "Tack"). The viscosity solve couples
// a paste particle to the instrument particles within h with no slip, which holds the paste to the
// instrument whatever the tension. Where the materials give their contact a strength sigma
// (Material::interface_strength), the contact slips in tension: after the solve, a paste particle
// whose tension against the instrument (the viscous pull of its instrument pairs and the pressure's
// push, along their mean line towards the instrument) is over sigma V_i^(2/3) (its share of the
// interface) has its instrument pairs' coupling weakened by the ratio that brings the tension to
// that (the rows' weights, their diagonal and fixed terms; the tool's rows read the same factor,
// finish.cpp), and the solve runs again, up to kPasses times, each pass weakening it further where
// the particle, now lagging, is still pulled harder. Only weakened, never pushed: no force is
// added, so nothing is drawn into the instrument. Nothing is remembered between steps.
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/iisph.hpp"
#include "solver/pressure_terms.hpp"

namespace dentsph::iisph {

InterfacePass cap_tool_pull(const Model& model, State& s, IisphScratch& x, int threads, bool first) {
  constexpr std::size_t stride = IisphScratch::kPairStride;
  const std::int64_t nm = std::int64_t(x.material.size());
  std::uint32_t weakened = 0, first_time = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : weakened, first_time)
  for (std::int64_t m = 0; m < nm; ++m) {
    const std::uint32_t i = x.material[m];
    if (first) x.interface_scale[i] = 1;
    SolverPair* row = x.pairs.data() + std::size_t(i) * stride;
    const std::size_t from = stride - x.n_other[i];
    const Material& paste = model.materials[s.material[i] & kMaterialMask];
    real strength = std::numeric_limits<real>::infinity();
    Vec3 line, viscous, pressure;  // the mean direction to the instrument's pairs, their forces on i
    const real vol = s.mass[i] * x.inv_rho[i];
    const Vec3 vi = x.v_a[i];
    for (std::size_t q = from; q < stride; ++q) {
      const std::uint32_t j = row[q].j;
      if (s.role[j] != Role::tool) continue;
      const real c = contact_strength(paste.interface_strength,
                                      model.materials[s.material[j] & kMaterialMask].interface_strength);
      if (c > 0) strength = std::min(strength, c);
      const Vec3 d = s.pos[j] - s.pos[i];
      const real r = norm(d);
      if (r > 0) line += d / r;
      const Vec3 g = row[q].grad();
      pressure -= g * (s.mass[i] * pair_q(x, i, j));  // pushes i off the instrument (p >= 0)
      if (x.rheology)
        viscous += g * (-vol * row[q].visc * dot(vi - s.vel[j], g));  // the projected form (rheology.cpp)
      else
        viscous += (s.vel[j] - vi) * (vol * row[q].visc);
    }
    const real len = norm(line);
    if (!std::isfinite(strength) || !(len > 0)) continue;
    const Vec3 n = line / len;
    // The contact's tension: the viscous pull less the pressure's push (a pressed contact whose
    // coupling holds the paste against the pressure is not pulled).
    const real hold = strength * std::cbrt(vol * vol), push = dot(pressure, n), pull = dot(viscous, n);
    if (!(pull + push > hold)) continue;
    const real f = std::clamp((hold - push) / pull, real(0), real(1));  // pull > hold - push >= hold > 0
    ++weakened;
    first_time += x.interface_scale[i] == 1;
    x.interface_scale[i] *= f;
    for (std::size_t q = from; q < stride; ++q) {
      const std::uint32_t j = row[q].j;
      if (s.role[j] != Role::tool) continue;
      const real c = row[q].visc, dc = c * (1 - f);
      if (x.rheology) {
        const Vec3 g = row[q].grad();
        x.visc_block[i] -= Vec3{g.x * g.x, g.y * g.y, g.z * g.z} * dc;
        x.visc_fixed[i] -= g * (dc * dot(s.vel[j], g));
      } else {
        x.visc_diag[i] -= dc;
        x.visc_fixed[i] -= s.vel[j] * dc;
      }
      row[q].visc = float(c * f);
    }
  }
  return {weakened, first_time};
}

}  // namespace dentsph::iisph
