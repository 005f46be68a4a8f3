// Stage 4 over all particles (pressure.hpp); the grid step applies it inside the density pass.
#include "step/pressure.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void compute_pressure(State& s, int threads) {
  const std::int64_t n = s.size();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) pressure_of(s, i);
}

}  // namespace dentsph::stages
