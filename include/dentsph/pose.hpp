// Rigid poses (position + unit quaternion) for the tool, and their interpolation.
#pragma once

#include "dentsph/vec3.hpp"

namespace dentsph {

// Unit quaternion w + (x, y, z).
struct Quat {
  real w = 1, x = 0, y = 0, z = 0;

  // Rotation by `angle_rad` about `axis` (need not be unit length, must be non-zero).
  static Quat from_axis_angle(const Vec3& axis, real angle_rad);
  Quat normalized() const;
  Vec3 rotate(const Vec3& v) const;
};

Quat operator*(const Quat& a, const Quat& b);
// Shortest-arc spherical interpolation, s in [0, 1].
Quat slerp(Quat a, const Quat& b, real s);

// A rigid transform: a point p in the body frame is at position + orientation.rotate(p).
struct Pose {
  Vec3 position;
  Quat orientation;

  Vec3 apply(const Vec3& p) const { return position + orientation.rotate(p); }
};

// The pose a fraction s in [0, 1] of the way from a to b: positions linearly, orientations by slerp.
Pose interpolate(const Pose& a, const Pose& b, real s);

}  // namespace dentsph
