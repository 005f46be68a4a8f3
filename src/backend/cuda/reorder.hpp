// Stage 2b on the GPU, per sorted index: gather the particle from the previous order into cell
// order, and record where its stable id now lives. The GPU holds no material table: it gathers
// the parameters mu, Kp, rho0, Ka with the material index (which the host State's cache follows). rho, pressure, volume and force are recomputed
// before they are read, so they are not gathered.
#pragma once

#include "backend/cuda/view.hpp"

namespace dentsph::gpu {

DENTSPH_HD inline void reorder_body(const StepView& v, std::uint32_t k) {
  const std::uint32_t o = v.order[k];
  const ParticleArrays& s = v.src;
  const ParticleArrays& d = v.p;
  d.id[k] = s.id[o];
  d.role[k] = s.role[o];
  d.pos[k] = s.pos[o];
  d.vel[k] = s.vel[o];
  d.anchor[k] = s.anchor[o];
  d.mass[k] = s.mass[o];
  d.material[k] = s.material[o];
  d.mu[k] = s.mu[o];
  d.Kp[k] = s.Kp[o];
  d.rho0[k] = s.rho0[o];
  d.Ka[k] = s.Ka[o];
  v.index_of_id[s.id[o]] = k;
}

}  // namespace dentsph::gpu
