// Uniform-grid helpers shared by the CPU stages and the CUDA backend: a particle's cell, its key,
// and a visit of the 27 cells around it.
#pragma once

#include <cmath>
#include <cstdint>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph::grid {

// Cell coordinate along one axis, wrapped into [0, dim). Exact for any finite coordinate (fmod
// of an integer-valued double is exact); a non-finite coordinate gets cell 0.
DENTSPH_HD inline int wrap_cell(real coord, real origin, real cell_size, int dim) {
  const real q = std::floor((coord - origin) / cell_size);
  real m = std::fmod(q, real(dim));
  if (m < 0) m += dim;
  if (!(m >= 0 && m < dim)) return 0;
  return int(m);
}

DENTSPH_HD inline std::uint32_t cell_key(int cx, int cy, int cz, const GridSpec& g) {
  return std::uint32_t((std::int64_t(cz) * g.dims[1] + cy) * g.dims[0] + cx);
}

DENTSPH_HD inline std::uint32_t key_of(const Vec3& p, const GridSpec& g) {
  return cell_key(wrap_cell(p.x, g.origin.x, g.cell_size, g.dims[0]),
                  wrap_cell(p.y, g.origin.y, g.cell_size, g.dims[1]),
                  wrap_cell(p.z, g.origin.z, g.cell_size, g.dims[2]), g);
}

// Calls fn(j) for every particle j in the 27 cells around position p (p's own particle
// included). The state must have been sorted and reordered this step.
template <class Fn>
inline void for_each_in_neighbourhood(const GridSpec& g, const GridIndex& gi, const Vec3& p, Fn&& fn) {
  const int c[3] = {wrap_cell(p.x, g.origin.x, g.cell_size, g.dims[0]),
                    wrap_cell(p.y, g.origin.y, g.cell_size, g.dims[1]),
                    wrap_cell(p.z, g.origin.z, g.cell_size, g.dims[2])};
  for (int dz = -1; dz <= 1; ++dz) {
    int z = c[2] + dz;
    z = z < 0 ? z + g.dims[2] : (z >= g.dims[2] ? z - g.dims[2] : z);
    for (int dy = -1; dy <= 1; ++dy) {
      int y = c[1] + dy;
      y = y < 0 ? y + g.dims[1] : (y >= g.dims[1] ? y - g.dims[1] : y);
      for (int dx = -1; dx <= 1; ++dx) {
        int x = c[0] + dx;
        x = x < 0 ? x + g.dims[0] : (x >= g.dims[0] ? x - g.dims[0] : x);
        const std::uint32_t key = cell_key(x, y, z, g);
        const std::uint32_t end = gi.cell_start[key + 1];
        for (std::uint32_t j = gi.cell_start[key]; j < end; ++j) fn(j);
      }
    }
  }
}

}  // namespace dentsph::grid
