// An increment's thickness, defined once (docs/assessment.md, "Increments"), for the cure's
// assessment, the procedure's increments and the report alike. The paste is divided into columns
// two spacings square along `up`, each of four cells a spacing square; a column holding n
// particles (each a spacing cubed of paste) in k of its cells is a layer n s^3 / (k s^2) = n s / k
// thick there: its paste's volume over the area the paste covers, so a gap inside it or a film
// drawn up a wall does not thicken it, and a column the paste half covers (at a wall) is not
// halved. The increment's thickness is the median over its columns, its thickest part the 90th
// percentile. A particle's depth in its increment is the same measure of the paste above it in its
// column, (particles above it) s / k, so a depth never lies beyond its column's thickness.
#pragma once

#include <cstdint>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph {

struct LayerThickness {
  real median = 0, p90 = 0;             // m, over the columns
  std::vector<std::uint32_t> column;    // each point's column, an index into `column_particles`
  std::vector<std::uint32_t> column_particles;  // particles in each column
  std::vector<std::uint32_t> column_cells;      // its cells holding paste, 1 to 4
  std::vector<real> depth;              // m, each point's depth: the paste above it in its column
  real spacing = 0;                     // m, the particles' spacing it was measured with
  real column_thickness(std::uint32_t c) const { return column_particles[c] * spacing / column_cells[c]; }
};

// The layer the `points` (m, world) make, measured along `up` (any length) with particles
// `spacing` apart (m). No points: all zero.
LayerThickness layer_thickness(const std::vector<Vec3>& points, const Vec3& up, real spacing);

}  // namespace dentsph
