// The material's colour field on the voxel grid: each particle spreads one particle volume
// (spacing^3) over its neighbourhood with the tensor-product cubic B-spline of knot spacing
// `spacing`, so the field is 1 inside material on the lattice of that spacing, whatever the
// lattice's offset against the voxels, 0 far from it, and 1/2 half a spacing beyond a flat
// surface layer: where the volume the particles stand for ends.
#pragma once

#include <vector>

#include "assess/voxels.hpp"

namespace dentsph::assess {

// The cubic B-spline of unit knot spacing: support (-2, 2), B(0) = 2/3, and the sum of
// B(x - j) over all integers j is 1 for every x (partition of unity).
inline real cubic_bspline(real x) {
  x = x < 0 ? -x : x;
  if (x < 1) return real(2) / 3 - x * x + real(0.5) * x * x * x;
  if (x < 2) return (2 - x) * (2 - x) * (2 - x) / 6;
  return 0;
}

// Adds every point (frame coordinates, m; non-finite ones skipped) to `field` ([g.size()],
// zeroed by the caller). Points farther than 2 spacings from the box add nothing.
void splat(const VoxelGrid& g, real spacing, const std::vector<Vec3>& points,
           std::vector<float>& field);

// The field at `at` (frame coordinates, m), interpolated trilinearly between voxel centres
// (clamped to the grid).
real sample(const VoxelGrid& g, const std::vector<float>& field, const Vec3& at);

}  // namespace dentsph::assess
