// Stage 4's law for one particle (docs/model.md, "One step", step 4; the paper, section 3.1): repulsion only,
// P = max(0, Kp (rho - rho0)), and the volume m / rho that every pair term needs. Written once for
// the CPU step (step/pressure_stage.hpp) and the CUDA stage body (backend/cuda/pressure.hpp).
#pragma once

#include "dentsph/config.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph::physics {

// Pa, from the stiffness Kp (m^2/s^2), the density and the rest density (kg/m^3). A NaN density
// gives 0, as max(0, NaN) did.
DENTSPH_HD inline real pressure(real Kp, real rho, real rho0) {
  const real P = Kp * (rho - rho0);
  return P > 0 ? P : real(0);
}

// m^3, m / rho.
DENTSPH_HD inline real volume(real mass, real rho) { return mass / rho; }

}  // namespace dentsph::physics
