#include "dentsph/pose.hpp"

#include <cmath>

namespace dentsph {

Quat Quat::from_axis_angle(const Vec3& axis, real angle_rad) {
  const real n = norm(axis);
  if (n == 0) return {};
  const real s = std::sin(0.5 * angle_rad) / n;
  return Quat{std::cos(0.5 * angle_rad), axis.x * s, axis.y * s, axis.z * s}.normalized();
}

Quat Quat::normalized() const {
  const real n = std::sqrt(w * w + x * x + y * y + z * z);
  if (n == 0) return {};
  return {w / n, x / n, y / n, z / n};
}

Vec3 Quat::rotate(const Vec3& v) const {
  // v' = v + 2 w (q x v) + 2 q x (q x v), q = (x, y, z).
  const Vec3 q{x, y, z};
  const Vec3 t = 2.0 * cross(q, v);
  return v + w * t + cross(q, t);
}

Quat operator*(const Quat& a, const Quat& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

Quat slerp(Quat a, const Quat& b, real s) {
  real c = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
  if (c < 0) {  // shortest arc
    a = {-a.w, -a.x, -a.y, -a.z};
    c = -c;
  }
  real wa = 1 - s, wb = s;
  if (c < 0.9995) {
    const real th = std::acos(c);
    const real sn = std::sin(th);
    wa = std::sin((1 - s) * th) / sn;
    wb = std::sin(s * th) / sn;
  }
  return Quat{wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z}.normalized();
}

Pose interpolate(const Pose& a, const Pose& b, real s) {
  return {a.position + s * (b.position - a.position), slerp(a.orientation, b.orientation, s)};
}

}  // namespace dentsph
