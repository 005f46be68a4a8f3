// Pair interactions of the force stage (docs/model.md, "One step", step 5), shared by every backend. Each returns
// the force density that j exerts on i, in N/m^3. m_i/rho_i times it is antisymmetric in (i, j),
// so internal forces conserve momentum.
#pragma once

#include "dentsph/state.hpp"
#include "physics/kernels.hpp"

namespace dentsph::pair {

// What a pair term needs to know about one side: position, velocity, volume m / rho (m^3),
// pressure, viscosity and adhesion strength. The grid step's density pass keeps one such record
// per particle (State's PairData, GridIndex::pair_data), so the two are one type.
using Side = PairData;

// One particle's Side from arrays indexed by particle that are named as a State names them (pos,
// vel, volume, pressure, mu, Ka): the State on the CPU, a view of the GPU's arrays there.
template <class Particles>
DENTSPH_HD inline Side side_of(const Particles& p, std::uint32_t i) {
  return {p.pos[i], p.vel[i], p.volume[i], p.pressure[i], p.mu[i], p.Ka[i]};
}

// Pressure (eq. 5, Mueller's symmetrised form) plus viscosity (eq. 4), for 0 < r < h.
// d = r_i - r_j, r = |d|.
DENTSPH_HD inline Vec3 pressure_viscosity(const Side& i, const Side& j, const Vec3& d, real r,
                                          const KernelCoeffs& k) {
  if (r >= k.h || r <= 0) return {};
  // -(P_i + P_j)/2 * m_j/rho_j * gradW_spiky, with gradW = radial * d / r.
  const real fp = -0.5 * (i.pressure + j.pressure) * j.vol * kernels::spiky_grad_radial(r, k) / r;
  const real fv = 0.5 * (i.mu + j.mu) * j.vol * kernels::visc_laplacian(r, k);
  return d * fp + (j.vel - i.vel) * fv;
}

// Adhesion (eq. 11) of a bonded pair: (Ka_i + Ka_j)/2 * m_j/rho_j * W_adh(r) * rhat.
DENTSPH_HD inline Vec3 adhesion(const Side& i, const Side& j, const Vec3& d, real r,
                                const AdhesionParams& a, const KernelCoeffs& k) {
  if (r <= 0) return {};
  const real w = kernels::adhesion(r, a, k);
  if (w == 0) return {};
  return d * (0.5 * (i.Ka + j.Ka) * j.vol * w / r);
}

// Whether a pair may bond at all: its mean adhesion strength is positive (so tool and wall,
// both with Ka = 0, never bond; docs/model.md, "Particles"), and at least one side is material (two
// particles that never move relative to each other, wall-wall or tool-tool, have nothing to
// hold together).
DENTSPH_HD inline bool can_bond(Role role_i, Role role_j, real Ka_i, real Ka_j) {
  return Ka_i + Ka_j > 0 && (role_i == Role::material || role_j == Role::material);
}

}  // namespace dentsph::pair
