// Small geometric primitives of the tooth module: nearest point on a triangle (with the feature
// it lies on, for the pseudo-normal sign), ray-triangle and ray-box tests, and the eigen
// decomposition of a symmetric 3x3 matrix.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include "dentsph/tooth.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph::tooth {

// The axis-aligned box around the eight corners of `b` mapped by `map` (a frame's to_world or
// to_local: a box of one frame as a box of the other).
template <class Map>
Bounds box_of_corners(const Bounds& b, Map map) {
  constexpr real inf = 1e300;
  Bounds out{{inf, inf, inf}, {-inf, -inf, -inf}};
  for (int k = 0; k < 8; ++k) {
    const Vec3 c = map(Vec3{k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y, k & 4 ? b.max.z : b.min.z});
    out.min = vmin(out.min, c);
    out.max = vmax(out.max, c);
  }
  return out;
}

inline Vec3 normalized(const Vec3& v) {
  const real n = norm(v);
  return n > 0 ? v / n : Vec3{};
}
// Plain comparisons rather than std::fmin / std::fmax: those honour NaN rules that keep the
// compiler from inlining them, and they sit in the innermost loop of every distance query.
inline real min2(real a, real b) { return b < a ? b : a; }
inline real max2(real a, real b) { return a < b ? b : a; }

// Where on a triangle the nearest point lies: which feature's pseudo-normal gives the sign.
enum class Feature : std::uint8_t { vertex0, vertex1, vertex2, edge01, edge12, edge20, face };

struct TrianglePoint {
  Vec3 point;
  Feature feature = Feature::face;
};

// Nearest point of triangle abc to p, by Voronoi regions (Ericson, Real-Time Collision
// Detection, 5.1.5). Degenerate triangles resolve to an edge or vertex.
inline TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                         const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const real d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {a, Feature::vertex0};
  const Vec3 bp = p - b;
  const real d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {b, Feature::vertex1};
  const real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + ab * (d1 / (d1 - d3)), Feature::edge01};
  const Vec3 cp = p - c;
  const real d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {c, Feature::vertex2};
  const real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + ac * (d2 / (d2 - d6)), Feature::edge20};
  const real va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return {b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), Feature::edge12};
  const real denom = va + vb + vc;
  if (!(std::fabs(denom) > 0)) return {a, Feature::vertex0};  // all three corners coincide
  const real v = vb / denom, w = vc / denom;
  return {a + ab * v + ac * w, Feature::face};
}

// Ray parameter t of the crossing of o + t d with triangle abc (Moeller and Trumbore 1997), if
// it lies in (t_min, t_max).
inline std::optional<real> ray_triangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                        const Vec3& c, real t_min, real t_max) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 q = cross(d, e2);
  const real det = dot(e1, q);
  if (std::fabs(det) < 1e-300) return std::nullopt;
  const real inv = 1 / det;
  const Vec3 s = o - a;
  // A hair of slack on the barycentric tests, so that a ray through a shared edge or vertex
  // hits at least one of the triangles there despite round-off.
  constexpr real slack = 1e-10;
  const real u = dot(s, q) * inv;
  if (u < -slack || u > 1 + slack) return std::nullopt;
  const Vec3 r = cross(s, e1);
  const real v = dot(d, r) * inv;
  if (v < -slack || u + v > 1 + slack) return std::nullopt;
  const real t = dot(e2, r) * inv;
  if (t <= t_min || t >= t_max) return std::nullopt;
  return t;
}

// Squared distance from p to the box [lo, hi] (0 inside).
inline real box_distance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const real ex = max2(max2(lo.x - p.x, 0.0), p.x - hi.x);
  const real ey = max2(max2(lo.y - p.y, 0.0), p.y - hi.y);
  const real ez = max2(max2(lo.z - p.z, 0.0), p.z - hi.z);
  return ex * ex + ey * ey + ez * ez;
}

// Entry parameter of o + t d into the box, if it meets the box within (-inf, t_max); inv_d is
// 1/d per component (infinite for a zero component).
inline bool ray_hits_box(const Vec3& o, const Vec3& inv_d, const Vec3& lo, const Vec3& hi,
                         real t_min, real t_max) {
  real t0 = t_min, t1 = t_max;
  for (int k = 0; k < 3; ++k) {
    real a = (lo[k] - o[k]) * inv_d[k], b = (hi[k] - o[k]) * inv_d[k];
    if (a > b) std::swap(a, b);
    if (std::isnan(a) || std::isnan(b)) {  // 0 * inf: the ray runs in the slab's plane
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    t0 = max2(t0, a);
    t1 = min2(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

using Mat3 = std::array<std::array<real, 3>, 3>;

// Eigen decomposition of a symmetric matrix by cyclic Jacobi rotations: values in descending
// order, vectors[i] the unit eigenvector of values[i].
struct Eigen3 {
  std::array<real, 3> values;
  std::array<Vec3, 3> vectors;
};
Eigen3 symmetric_eigen(Mat3 a);

}  // namespace dentsph::tooth
