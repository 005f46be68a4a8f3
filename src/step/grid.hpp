// Uniform-grid helpers shared by the CPU stages and the CUDA backend: a particle's cell, its
// bucket key, and visits of the cells around a position.
#pragma once

#include <cmath>
#include <cstdint>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph::grid {

// Cell coordinate along one axis, wrapped into [0, dim). Exact for any finite coordinate; a
// non-finite coordinate gets cell 0. The common case (within a billion cells of the origin)
// takes an integer path; beyond it fmod of the integer-valued floor is still exact.
DENTSPH_HD inline int wrap_cell(real coord, real origin, real cell_size, int dim) {
  const real q = std::floor((coord - origin) / cell_size);
  if (q > -1e9 && q < 1e9) {
    int c = int(q) % dim;
    return c < 0 ? c + dim : c;
  }
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

// Sort bucket of a particle: moving particles first in their cell, static boundary after.
DENTSPH_HD inline std::uint32_t bucket_of(const Vec3& p, Role role, const GridSpec& g) {
  return 2 * key_of(p, g) + (role == Role::boundary ? 1 : 0);
}

// Wraps a cell coordinate at most one period outside [0, dim) back into it.
DENTSPH_HD inline int wrap(int c, int dim) { return c < 0 ? c + dim : (c >= dim ? c - dim : c); }

// Which particles of each cell a visit wants.
enum class Visit { all, moving, boundary };

// Calls range(begin, end) for runs of sorted indices covering the particles of the
// (2 reach + 1)^3 cells around p (p's own particle included) of the kind `visit` asks for.
// Where the cells of a row are adjacent in memory (no wrap in x) and all particles are wanted,
// a row is one run.
template <class Range>
inline void for_each_neighbour_range(const GridSpec& g, const GridIndex& gi, const Vec3& p, Visit visit,
                                     Range&& range) {
  const int R = g.reach;
  const int cx = wrap_cell(p.x, g.origin.x, g.cell_size, g.dims[0]);
  const int cy = wrap_cell(p.y, g.origin.y, g.cell_size, g.dims[1]);
  const int cz = wrap_cell(p.z, g.origin.z, g.cell_size, g.dims[2]);
  const std::uint32_t* bs = gi.bucket_start.data();
  const bool row_contiguous = visit == Visit::all && cx >= R && cx + R < g.dims[0];
  for (int dz = -R; dz <= R; ++dz) {
    const int z = wrap(cz + dz, g.dims[2]);
    for (int dy = -R; dy <= R; ++dy) {
      const int y = wrap(cy + dy, g.dims[1]);
      if (row_contiguous) {
        const std::uint32_t k = cell_key(cx - R, y, z, g);
        range(bs[2 * k], bs[2 * (k + 2 * R + 1)]);
        continue;
      }
      for (int dx = -R; dx <= R; ++dx) {
        const std::uint32_t k = cell_key(wrap(cx + dx, g.dims[0]), y, z, g);
        switch (visit) {
          case Visit::all: range(bs[2 * k], bs[2 * k + 2]); break;
          case Visit::moving: range(bs[2 * k], bs[2 * k + 1]); break;
          case Visit::boundary: range(bs[2 * k + 1], bs[2 * k + 2]); break;
        }
      }
    }
  }
}

// Calls fn(j) for every particle j of the cells around p that `visit` asks for.
template <class Fn>
inline void for_each_in_neighbourhood(const GridSpec& g, const GridIndex& gi, const Vec3& p, Visit visit, Fn&& fn) {
  for_each_neighbour_range(g, gi, p, visit, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t j = b; j < e; ++j) fn(j);
  });
}

}  // namespace dentsph::grid
