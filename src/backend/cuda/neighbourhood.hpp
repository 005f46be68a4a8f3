// The cells around a position on the GPU's grid, host and device: the (2 reach + 1)^3 cells of
// step/grid.hpp, each cell's particles in two buckets (moving first, static boundary after), each
// bucket a range [bucket_begin, bucket_end) of sorted indices (empty buckets are [0, 0)).
#pragma once

#include "backend/cuda/view.hpp"
#include "step/grid.hpp"

namespace dentsph::gpu {

// Calls fn(j) for every sorted index j in the cells around p of the kind `visit` asks for (p's own
// particle included).
template <class Fn>
DENTSPH_HD inline void for_each_neighbour(const StepView& v, const Vec3& p, grid::Visit visit, Fn&& fn) {
  const GridSpec& g = v.grid;
  const int R = g.reach;
  const int cx = grid::wrap_cell(p.x, g.origin.x, g.cell_size, g.dims[0]);
  const int cy = grid::wrap_cell(p.y, g.origin.y, g.cell_size, g.dims[1]);
  const int cz = grid::wrap_cell(p.z, g.origin.z, g.cell_size, g.dims[2]);
  const std::uint32_t first = visit == grid::Visit::boundary ? 1 : 0;  // bucket 2k + first ...
  const std::uint32_t last = visit == grid::Visit::moving ? 0 : 1;     // ... to 2k + last
  for (int dz = -R; dz <= R; ++dz) {
    const int z = grid::wrap(cz + dz, g.dims[2]);
    for (int dy = -R; dy <= R; ++dy) {
      const int y = grid::wrap(cy + dy, g.dims[1]);
      for (int dx = -R; dx <= R; ++dx) {
        const std::uint32_t k = grid::cell_key(grid::wrap(cx + dx, g.dims[0]), y, z, g);
        for (std::uint32_t b = 2 * k + first; b <= 2 * k + last; ++b) {
          const std::uint32_t end = v.bucket_end[b];
          for (std::uint32_t j = v.bucket_begin[b]; j < end; ++j) fn(j);
        }
      }
    }
  }
}

}  // namespace dentsph::gpu
