// Stage 4: P_i = max(0, Kp_i (rho_i - rho0_i)), repulsion only (the paper, section 3.1).
#include <algorithm>

#include "step/stages.hpp"

namespace dentsph::stages {

void compute_pressure(State& s) {
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) s.pressure[i] = std::max<real>(0, s.Kp[i] * (s.rho[i] - s.rho0[i]));
}

}  // namespace dentsph::stages
