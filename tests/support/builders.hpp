// Small programmatic scenes for tests: a model with chosen parameters and particles on lattices
// or at random, without going through the scene file format.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "dentsph/model.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/state.hpp"

namespace dentsph::testing {

// A model of spacing s (set_lattice_spacing: h = 2 s, A = 1.2 s, B = 3 s), over the given domain.
inline ModelParams params_for_spacing(real s, Vec3 lo, Vec3 hi, real dt = 1e-4, Vec3 g = {0, 0, 0}) {
  ModelParams p;
  p.dt = dt;
  set_lattice_spacing(p, s);
  p.gravity = g;
  p.domain_min = lo;
  p.domain_max = hi;
  return p;
}

inline ParticleInit particle(Role role, Vec3 pos, real mass, Material m, Vec3 vel = {}) {
  return make_particle(role, pos, mass, m, vel);
}

// Points lo + s*(i,j,k) for 0 <= i < n[0] etc.
inline std::vector<Vec3> lattice(Vec3 lo, real s, int nx, int ny, int nz) {
  std::vector<Vec3> pts;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) pts.push_back(lo + Vec3{i * s, j * s, k * s});
  return pts;
}

// Shell of `layers` lattice layers around the inner box [lo, lo + s*n] (walls start one spacing
// outside it), open at the top.
inline std::vector<Vec3> open_container(Vec3 lo, real s, int nx, int ny, int nz, int layers) {
  std::vector<Vec3> pts;
  for (int k = -layers; k <= nz; ++k)
    for (int j = -layers; j <= ny + layers; ++j)
      for (int i = -layers; i <= nx + layers; ++i) {
        const bool inside = i >= 0 && i <= nx && j >= 0 && j <= ny && k >= 0;
        if (!inside) pts.push_back(lo + Vec3{i * s, j * s, k * s});
      }
  return pts;
}

// A column of `liquid`, nx x nx x nz particles of spacing s from the origin, in an open container of
// `wall` two layers deep and two spacings taller than it; every particle of the lattice mass of the
// liquid's rest density (lattice_particle_mass).
inline std::vector<ParticleInit> column_in_container(const Model& model, real s, int nx, int nz, const Material& liquid,
                                                     const Material& wall) {
  const real m = lattice_particle_mass(liquid.rho0, s, model.kernel);
  std::vector<ParticleInit> ps;
  for (Vec3 x : lattice({0, 0, 0}, s, nx, nx, nz)) ps.push_back(particle(Role::material, x, m, liquid));
  for (Vec3 x : open_container({0, 0, 0}, s, nx - 1, nx - 1, nz + 2, 2)) ps.push_back(particle(Role::boundary, x, m, wall));
  return ps;
}

inline Vec3 random_in_box(std::mt19937_64& rng, Vec3 lo, Vec3 hi) {
  std::uniform_real_distribution<real> u(0, 1);
  return {lo.x + (hi.x - lo.x) * u(rng), lo.y + (hi.y - lo.y) * u(rng), lo.z + (hi.z - lo.z) * u(rng)};
}

inline Vec3 total_momentum(const State& s) {
  Vec3 p;
  for (std::uint32_t i = 0; i < s.size(); ++i) p += s.vel[i] * s.mass[i];
  return p;
}

// Index of each stable id, for comparing states whose order differs.
inline std::uint32_t at(const State& s, std::uint32_t id) { return s.index_of_id[id]; }

}  // namespace dentsph::testing
