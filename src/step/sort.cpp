// Stage 2a: sort particles by cell key. Keys are below the (bounded) cell count, so a single
// counting pass is a radix sort with one digit; it is stable, O(n + cells), and its prefix sums
// are exactly the cell ranges the neighbour loops need (cell_start[k] .. cell_start[k + 1]).
#include <algorithm>

#include "step/stages.hpp"

namespace dentsph::stages {

void sort_by_cell(const Model& model, State& state) {
  GridIndex& g = state.grid;
  const std::uint32_t n = state.size();
  const std::size_t cells = std::size_t(model.grid.cell_count());
  std::fill(g.cell_start.begin(), g.cell_start.end(), 0u);
  for (std::uint32_t i = 0; i < n; ++i) ++g.cell_start[g.key[i] + 1];
  for (std::size_t c = 0; c < cells; ++c) g.cell_start[c + 1] += g.cell_start[c];
  std::copy(g.cell_start.begin(), g.cell_start.end() - 1, g.cell_fill.begin());
  for (std::uint32_t i = 0; i < n; ++i) g.order[g.cell_fill[g.key[i]]++] = i;
}

}  // namespace dentsph::stages
