// Stage 2a: sort particles by bucket. Buckets are below twice the (bounded) cell count, so a
// single counting pass is a radix sort with one digit; it is stable, O(n + cells), and its
// prefix sums are exactly the ranges the neighbour loops need (bucket_start[b] .. [b + 1]).
#include <algorithm>

#include "step/stages.hpp"

namespace dentsph::stages {

void sort_by_cell(const Model& model, State& state) {
  GridIndex& g = state.grid;
  const std::uint32_t n = state.size();
  const std::size_t buckets = 2 * std::size_t(model.grid.cell_count());
  std::fill(g.bucket_start.begin(), g.bucket_start.end(), 0u);
  for (std::uint32_t i = 0; i < n; ++i) ++g.bucket_start[g.key[i] + 1];
  for (std::size_t b = 0; b < buckets; ++b) g.bucket_start[b + 1] += g.bucket_start[b];
  std::copy(g.bucket_start.begin(), g.bucket_start.end() - 1, g.bucket_fill.begin());
  for (std::uint32_t i = 0; i < n; ++i) g.order[g.bucket_fill[g.key[i]]++] = i;
}

}  // namespace dentsph::stages
