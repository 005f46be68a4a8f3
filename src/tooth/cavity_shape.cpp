// Rounded slanted boxes and their union (see cavity_shape.hpp).
#include "tooth/cavity_shape.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "tooth/geometry.hpp"

namespace dentsph::tooth {

RoundedBox::RoundedBox(const SlantedBox& box, real radius, const char* what)
    : box_(box), radius_(radius) {
  // Shrinking a plane x <= a + s z by r along its unit normal (1, 0, -s) / sqrt(1 + s^2)
  // lowers a by r sqrt(1 + s^2).
  auto shrink = [&](Side side, real sign) {
    side.a -= sign * radius * std::sqrt(1 + side.slope * side.slope);
    return side;
  };
  const Side xl = shrink(box.x_lo, -1), xh = shrink(box.x_hi, 1), yl = shrink(box.y_lo, -1),
             yh = shrink(box.y_hi, 1);
  const real zl = box.z_lo + radius, zh = box.z_hi - radius;
  for (real z : {zl, zh}) {
    const real wx = xh.at(z) - xl.at(z), wy = yh.at(z) - yl.at(z);
    if (zh < zl || wx < 0 || wy < 0) {
      const real room =
          std::fmin(std::fmin(box.x_hi.at(z) - box.x_lo.at(z), box.y_hi.at(z) - box.y_lo.at(z)),
                    box.z_hi - box.z_lo);
      throw CavityError(fmt::format(
          "{}: the rounding radius {:.3f} mm does not fit: the box is only {:.3f} mm across at "
          "its narrowest; use a rounding of at most about {:.3f} mm, or widen the box",
          what, radius * 1e3, room * 1e3, room / 2 * 1e3 * 0.95));
    }
  }
  auto plane = [](real nx, real ny, real nz, real off) {
    const real l = std::sqrt(nx * nx + ny * ny + nz * nz);
    return std::pair{Vec3{nx / l, ny / l, nz / l}, off / l};
  };
  const std::pair<Vec3, real> planes[6] = {
      plane(-1, 0, xl.slope, -xl.a), plane(1, 0, -xh.slope, xh.a), plane(0, -1, yl.slope, -yl.a),
      plane(0, 1, -yh.slope, yh.a),  plane(0, 0, -1, -zl),         plane(0, 0, 1, zh)};
  for (int k = 0; k < 6; ++k) std::tie(normal_[k], offset_[k]) = planes[k];
  // Corner (i, j, k): x side i, y side j, height k.
  auto corner = [&](int i, int j, int k) {
    const real z = k ? zh : zl;
    return Vec3{(i ? xh : xl).at(z), (j ? yh : yl).at(z), z};
  };
  const int quads[6][4][3] = {
      {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}},
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  constexpr real inf = std::numeric_limits<real>::infinity();
  core_bounds_ = {{inf, inf, inf}, {-inf, -inf, -inf}};
  for (int f = 0; f < 6; ++f) {
    Vec3 c[4];
    for (int v = 0; v < 4; ++v) {
      c[v] = corner(quads[f][v][0], quads[f][v][1], quads[f][v][2]);
      core_bounds_.min = vmin(core_bounds_.min, c[v]);
      core_bounds_.max = vmax(core_bounds_.max, c[v]);
    }
    faces_[2 * f] = {c[0], c[1], c[2]};
    faces_[2 * f + 1] = {c[0], c[2], c[3]};
  }
}

RoundedBox::Sample RoundedBox::distance(const Vec3& p) const {
  real worst = -std::numeric_limits<real>::infinity();
  int worst_k = 0;
  for (int k = 0; k < 6; ++k) {
    const real d = dot(normal_[k], p) - offset_[k];
    if (d > worst) worst = d, worst_k = k;
  }
  if (worst <= 0) return {worst - radius_, normal_[worst_k]};
  real best2 = std::numeric_limits<real>::infinity();
  Vec3 best;
  for (const auto& f : faces_) {
    const Vec3 q = closest_on_triangle(p, f[0], f[1], f[2]).point;
    const real d2 = norm2(p - q);
    if (d2 < best2) best2 = d2, best = q;
  }
  const real d = std::sqrt(best2);
  return {d - radius_, d > 0 ? (p - best) / d : normal_[worst_k]};
}

Bounds RoundedBox::bounds() const {
  const Vec3 r{radius_, radius_, radius_};
  return {core_bounds_.min - r, core_bounds_.max + r};
}

RoundedBox::Sample CavityShape::distance(const Vec3& local) const {
  RoundedBox::Sample best{std::numeric_limits<real>::infinity(), {}};
  for (const RoundedBox& b : boxes) {
    const auto s = b.distance(local);
    if (s.distance < best.distance) best = s;
  }
  return best;
}

Bounds CavityShape::bounds() const {
  Bounds out = boxes.at(0).bounds();
  for (const RoundedBox& b : boxes) {
    out.min = vmin(out.min, b.bounds().min);
    out.max = vmax(out.max, b.bounds().max);
  }
  return out;
}

}  // namespace dentsph::tooth
