// Stage 1, broad phase: each particle's cell key on the uniform grid.
#include "step/grid.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void compute_cell_keys(const Model& model, State& state) {
  const std::uint32_t n = state.size();
  for (std::uint32_t i = 0; i < n; ++i) state.grid.key[i] = grid::key_of(state.pos[i], model.grid);
}

}  // namespace dentsph::stages
