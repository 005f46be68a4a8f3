// Simple cubic lattices of particles filling the scene's shapes (docs/scene-format.md,
// "Shapes"). Pure geometry: no JSON, no materials. Every point is base + spacing * (i, j, k) for
// integer i, j, k, so blocks of equal spacing and aligned bases share one lattice.
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "dentsph/limits.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph::scene {

// The most points one block may produce (dentsph/limits.hpp).
inline constexpr std::int64_t max_block_points = std::int64_t(limits::max_block_points);

// Points min + s (i, j, k), i, j, k >= 0, every coordinate <= max (+1e-9 s for rounding).
struct BoxShape {
  Vec3 min, max;  // m
};

// Points center + s (i, j, k), any sign, at distance <= radius (+1e-9 s) from the centre.
struct SphereShape {
  Vec3 center;      // m
  real radius = 0;  // m
};

// Points origin + s (i, j, k), 0 <= i < count[0] etc.
struct LatticeShape {
  Vec3 origin;                        // m
  std::int64_t count[3] = {0, 0, 0};  // points per axis
};

// Walls `layers` thick around the inner box [min, max]: with n = round((max - min) / s) per
// axis, the points min + s (i, j, k), i in [-layers, n_x + layers] (j likewise), k in
// [-layers, n_z + (open_top ? 0 : layers)], outside the inner index range [0, n] on some axis.
// The innermost wall layer lies one spacing outside [min, max], so a box block of the same
// spacing filling [min, max] sits at the lattice distance from it.
struct ContainerShape {
  Vec3 min, max;  // m
  int layers = 2;
  bool open_top = true;
};

using Shape = std::variant<BoxShape, SphereShape, LatticeShape, ContainerShape>;

// Number of points sample() gives, computed without generating them. In floating point so that
// absurd sizes compare as large instead of overflowing; exact below 2^53.
double point_count(const Shape& shape, real spacing);

// The points, x fastest, then y, then z. Call only when point_count() is acceptable.
std::vector<Vec3> sample(const Shape& shape, real spacing);

// Inner cells per axis of a container: round((max - min) / spacing), as a real so that absurd
// sizes cannot overflow.
real container_cells(real lo, real hi, real spacing);

}  // namespace dentsph::scene
