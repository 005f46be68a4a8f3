// The cavity's shape as an implicit solid with an exact signed distance: a union of rounded,
// slanted boxes in the tooth frame (z along the long axis, 0 at the occlusal reference).
#pragma once

#include <array>
#include <vector>

#include "dentsph/tooth.hpp"

namespace dentsph::tooth {

// A linear bound a + slope * z on x or y.
struct Side {
  real a = 0;      // m, value at z = 0
  real slope = 0;  // dimensionless, change per unit height
  real at(real z) const { return a + slope * z; }
};

// The solid {x_lo(z) <= x <= x_hi(z), y_lo(z) <= y <= y_hi(z), z_lo <= z <= z_hi}: every
// horizontal section is an axis-aligned rectangle, every side plane tilts in its own plane (the
// taper). Before rounding.
struct SlantedBox {
  Side x_lo, x_hi, y_lo, y_hi;
  real z_lo = 0, z_hi = 0;  // m
};

// A slanted box with every edge and corner rounded by `radius`: the Minkowski sum of the box
// shrunk by `radius` (its "core") with a ball. Its signed distance is the core's minus the
// radius, and the core's is exact: the largest plane distance inside, the distance to the
// nearest of its 12 face triangles outside. So the distance is exact everywhere.
class RoundedBox {
 public:
  // Throws CavityError (reason in `what`) when the core is empty: radius too large.
  RoundedBox(const SlantedBox& box, real radius, const char* what);

  struct Sample {
    real distance;  // m, negative inside
    Vec3 gradient;  // unit
  };
  Sample distance(const Vec3& p) const;
  const SlantedBox& box() const { return box_; }
  real radius() const { return radius_; }
  Bounds bounds() const;  // of the rounded solid

 private:
  SlantedBox box_;
  real radius_ = 0;
  std::array<Vec3, 6> normal_;  // unit outward normals of the core's planes
  std::array<real, 6> offset_;  // core: dot(normal, p) <= offset
  std::array<std::array<Vec3, 3>, 12> faces_;
  Bounds core_bounds_;
};

// Union of rounded boxes: the distance outside the union is the least of theirs (exact);
// inside, the least is a bound (overlaps), which is all the carving needs there.
struct CavityShape {
  std::vector<RoundedBox> boxes;
  RoundedBox::Sample distance(const Vec3& local) const;
  Bounds bounds() const;  // local
};

}  // namespace dentsph::tooth
