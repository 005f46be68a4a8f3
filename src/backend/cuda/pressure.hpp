// Stage 4 on the GPU, per particle: P_i = max(0, Kp_i (rho_i - rho0_i)) and V_i = m_i / rho_i
// (physics/pressure_law.hpp, as the CPU's step/pressure_stage.hpp).
#pragma once

#include "backend/cuda/view.hpp"
#include "physics/pressure_law.hpp"

namespace dentsph::gpu {

DENTSPH_HD inline void pressure_body(const StepView& v, std::uint32_t i) {
  v.pressure[i] = physics::pressure(v.p.Kp[i], v.rho[i], v.p.rho0[i]);
  v.volume[i] = physics::volume(v.p.mass[i], v.rho[i]);
}

}  // namespace dentsph::gpu
