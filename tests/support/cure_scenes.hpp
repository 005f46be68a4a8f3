// Paste for the cure tests: a slab of paste on a lattice (optionally on a floor of boundary
// particles), a light above it, and a loop that cures it at rest (no steps in between) or steps it.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "dentsph/cure.hpp"
#include "dentsph/scene.hpp"
#include "support/builders.hpp"

namespace dentsph::testing {

inline const Material kPaste{1.0, 10, 2000, 50};
inline const Material kWall{1.0, 15, 2000, 0};

// A scene's worth of model for paste of spacing s in [lo, hi] (h = 2 s), gravity down.
inline Model cure_model(real s, Vec3 lo, Vec3 hi, real dt = 5e-5) {
  return make_model(params_for_spacing(s, lo, hi, dt, {0, 0, -9.81}));
}

// Paste particles on the lattice of spacing s filling x, y in [0, nx s) and z from z0 up, `layers`
// layers (centres at half spacings), added as one increment (begin_increment).
inline void add_paste_layers(Model& model, State& st, real s, int nx, int ny, real z0, int layers,
                             const Material& paste = kPaste) {
  const real m = lattice_particle_mass(paste.rho0, s, model.kernel);
  std::vector<ParticleInit> ps;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        ps.push_back(make_particle(Role::material, {(i + 0.5) * s, (j + 0.5) * s, z0 + (k + 0.5) * s}, m, paste));
  const std::uint32_t first = st.size();
  st.add_particles(model, ps);
  st.cure.begin_increment(first, st.size() - first);
}

// Boundary particles (the tooth, or a mould) on the lattice: x, y in [0, nx s), `layers` layers
// below z0 (centres at half spacings).
inline void add_floor(Model& model, State& st, real s, int nx, int ny, real z0, int layers) {
  const real m = lattice_particle_mass(kWall.rho0, s, model.kernel);
  std::vector<ParticleInit> ps;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        ps.push_back(make_particle(Role::boundary, {(i + 0.5) * s, (j + 0.5) * s, z0 - (k + 0.5) * s}, m, kWall));
  st.add_particles(model, ps);
}

// A light straight down onto the point (x, y, z_top).
inline CuringLight light_above(Vec3 at, real irradiance_mw = 1000, real diameter = 10e-3) {
  CuringLight l;
  l.tip = at;
  l.direction = {0, 0, -1};
  l.irradiance = irradiance_mw * W_per_m2_per_mW_per_cm2;
  l.diameter = diameter;
  return l;
}

// Cures `st` at rest for `seconds` in updates of `dt` (the paste does not move; no step).
inline void cure_at_rest(const CureModel& cm, State& st, const std::optional<CuringLight>& light, real seconds,
                         real dt = 0.05) {
  const long n = std::max(1L, std::lround(seconds / dt));
  for (long k = 0; k < n; ++k) {
    st.time += seconds / real(n);
    cure_between_steps(cm, st, light, seconds / real(n));
  }
}

}  // namespace dentsph::testing
