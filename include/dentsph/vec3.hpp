// A small 3-vector usable in host and device code (no globals, no allocation).
#pragma once

#include <cmath>

#include "dentsph/config.hpp"

namespace dentsph {

struct Vec3 {
  real x = 0, y = 0, z = 0;

  constexpr Vec3() = default;  // defaulted: host and device alike
  DENTSPH_HD constexpr Vec3(real x_, real y_, real z_) : x(x_), y(y_), z(z_) {}

  DENTSPH_HD constexpr Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  DENTSPH_HD constexpr Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  DENTSPH_HD constexpr Vec3& operator*=(real s) { x *= s; y *= s; z *= s; return *this; }
  DENTSPH_HD constexpr real operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

DENTSPH_HD constexpr Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
DENTSPH_HD constexpr Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
DENTSPH_HD constexpr Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
DENTSPH_HD constexpr Vec3 operator*(Vec3 a, real s) { return a *= s; }
DENTSPH_HD constexpr Vec3 operator*(real s, Vec3 a) { return a *= s; }
DENTSPH_HD constexpr Vec3 operator/(const Vec3& a, real s) { return {a.x / s, a.y / s, a.z / s}; }
DENTSPH_HD constexpr bool operator==(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

DENTSPH_HD constexpr real dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
DENTSPH_HD constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
DENTSPH_HD constexpr real norm2(const Vec3& a) { return dot(a, a); }
DENTSPH_HD inline real norm(const Vec3& a) { return std::sqrt(norm2(a)); }
DENTSPH_HD inline bool is_finite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
// Whether p lies in the box [lo, hi] (faces included; false for NaN).
// Component-wise minimum and maximum (plain comparisons: inlined in the tooth's distance queries).
DENTSPH_HD constexpr Vec3 vmin(const Vec3& a, const Vec3& b) {
  return {b.x < a.x ? b.x : a.x, b.y < a.y ? b.y : a.y, b.z < a.z ? b.z : a.z};
}
DENTSPH_HD constexpr Vec3 vmax(const Vec3& a, const Vec3& b) {
  return {a.x < b.x ? b.x : a.x, a.y < b.y ? b.y : a.y, a.z < b.z ? b.z : a.z};
}
DENTSPH_HD constexpr bool inside(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
}
// The distance from p to the box [lo, hi] (0 inside it).
DENTSPH_HD inline real box_distance(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return norm(vmax(vmax(lo - p, p - hi), Vec3{}));
}

}  // namespace dentsph
