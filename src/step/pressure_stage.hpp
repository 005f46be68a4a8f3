// Stage 4 for one particle: P_i = max(0, Kp_i (rho_i - rho0_i)), repulsion only (the paper,
// section 3.1; physics/pressure_law.hpp), and its volume m_i / rho_i, which every pair term of the force pass needs. It
// needs particle i's density alone, so the grid step's density pass applies it as soon as rho_i is
// known; the all-pairs reference applies it in a pass of its own (brute_force.cpp).
#pragma once

#include <cstdint>

#include "dentsph/state.hpp"
#include "physics/pressure_law.hpp"

namespace dentsph::stages {

inline void pressure_of(State& s, std::int64_t i) {
  s.pressure[i] = physics::pressure(s.Kp[i], s.rho[i], s.rho0[i]);
  s.volume[i] = physics::volume(s.mass[i], s.rho[i]);
}

}  // namespace dentsph::stages
