// Mean neighbour count, for benchmarks and reports (the paper's Fig. 3 axis).
#include "dentsph/step.hpp"
#include "step/grid.hpp"
#include "step/stages.hpp"

namespace dentsph {

real mean_neighbours(const Model& model, State& state) {
  if (state.size() == 0) return 0;
  stages::compute_cell_keys(model, state, 1);
  stages::sort_by_cell(model, state);
  stages::reorder(model, state, 1);
  state.grid.lists_valid = false;  // sorted anew: the lists no longer match the order
  std::uint64_t pairs = 0;
  for (std::uint32_t i = 0; i < state.size(); ++i)
    grid::for_each_in_neighbourhood(model.grid, state.grid, state.pos[i], grid::Visit::all, [&](std::uint32_t j) {
      pairs += (j != i && norm2(state.pos[i] - state.pos[j]) < model.kernel.h2) ? 1 : 0;
    });
  return real(pairs) / state.size();
}

}  // namespace dentsph
