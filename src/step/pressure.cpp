// Stage 4: P_i = max(0, Kp_i (rho_i - rho0_i)), repulsion only (the paper, section 3.1); and each
// particle's volume m_i / rho_i, which every pair term of the force pass needs.
#include <algorithm>

#include "step/stages.hpp"

namespace dentsph::stages {

void compute_pressure(State& s, int threads) {
  const std::int64_t n = s.size();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    s.pressure[i] = std::max<real>(0, s.Kp[i] * (s.rho[i] - s.rho0[i]));
    s.volume[i] = s.mass[i] / s.rho[i];
  }
}

}  // namespace dentsph::stages
