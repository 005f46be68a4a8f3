// Stage 1, broad phase: each particle's sort bucket on the uniform grid (its cell, and whether
// it is a static boundary particle).
#include "step/grid.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void compute_cell_keys(const Model& model, State& state, int threads) {
  const std::int64_t n = state.size();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) state.grid.key[i] = grid::bucket_of(state.pos[i], state.role[i], model.grid);
}

}  // namespace dentsph::stages
