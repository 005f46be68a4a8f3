// Stage 4 on the GPU, per particle: P_i = max(0, Kp_i (rho_i - rho0_i)) and V_i = m_i / rho_i
// (the CPU's pressure.cpp).
#pragma once

#include "backend/cuda/view.hpp"

namespace dentsph::gpu {

DENTSPH_HD inline void pressure_body(const StepView& v, std::uint32_t i) {
  const real P = v.p.Kp[i] * (v.rho[i] - v.p.rho0[i]);
  v.pressure[i] = P > 0 ? P : real(0);
  v.volume[i] = v.p.mass[i] / v.rho[i];
}

}  // namespace dentsph::gpu
