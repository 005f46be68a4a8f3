// WallField (dentsph/wall_field.hpp).
#include "dentsph/wall_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace dentsph {

WallField::WallField(const std::function<real(const Vec3&)>& distance, Vec3 lo, Vec3 hi, real cell, real clearance,
                     std::int64_t max_nodes)
    : origin_(lo), cell_(cell), inv_cell_(1 / cell), clearance_(clearance) {
  if (!(cell > 0) || !std::isfinite(cell))
    throw std::invalid_argument(fmt::format("wall field: cell {} m is not a positive length", cell));
  if (!(clearance >= 0) || !std::isfinite(clearance))
    throw std::invalid_argument(fmt::format("wall field: clearance {} m is not a length", clearance));
  const real span[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  std::int64_t total = 1;
  for (int a = 0; a < 3; ++a) {
    if (!(span[a] > 0) || !std::isfinite(span[a]))
      throw std::invalid_argument("wall field: the box is empty: give walls to sample");
    const real n = std::ceil(span[a] / cell) + 1;
    if (!(n <= real(max_nodes)))
      throw std::invalid_argument(fmt::format("wall field: {} corners along one axis, more than {}", n, max_nodes));
    n_[a] = int(n);
    total *= n_[a];
    if (total > max_nodes)
      throw std::invalid_argument(
          fmt::format("wall field: more than {} corners for cells of {} m: use larger cells", max_nodes, cell));
  }
  phi_.resize(std::size_t(total));
  const std::int64_t planes = n_[2];
#pragma omp parallel for schedule(dynamic)
  for (std::int64_t k = 0; k < planes; ++k)
    for (int j = 0; j < n_[1]; ++j)
      for (int i = 0; i < n_[0]; ++i)
        phi_[(std::size_t(k) * n_[1] + j) * n_[0] + i] =
            float(distance(lo + Vec3{real(i) * cell, real(j) * cell, real(k) * cell}));
}

bool WallField::sample(const Vec3& p, real& distance, Vec3& gradient) const {
  const real g[3] = {(p.x - origin_.x) * inv_cell_, (p.y - origin_.y) * inv_cell_, (p.z - origin_.z) * inv_cell_};
  int c[3];
  real f[3];
  for (int a = 0; a < 3; ++a) {
    if (!(g[a] >= 0) || !(g[a] <= real(n_[a] - 1))) return false;  // outside, or not a number
    c[a] = std::min(int(g[a]), n_[a] - 2);
    f[a] = g[a] - real(c[a]);
  }
  const std::size_t sx = 1, sy = std::size_t(n_[0]), sz = sy * std::size_t(n_[1]);
  const std::size_t base = std::size_t(c[2]) * sz + std::size_t(c[1]) * sy + std::size_t(c[0]);
  real v[2][2][2];
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) v[k][j][i] = real(phi_[base + k * sz + j * sy + i * sx]);
  // Trilinear: along x, then y, then z; the gradient from the same corners.
  real x0[2][2], dx[2][2];
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j) {
      x0[k][j] = v[k][j][0] + f[0] * (v[k][j][1] - v[k][j][0]);
      dx[k][j] = v[k][j][1] - v[k][j][0];
    }
  const real y0 = x0[0][0] + f[1] * (x0[0][1] - x0[0][0]), y1 = x0[1][0] + f[1] * (x0[1][1] - x0[1][0]);
  const real gx0 = dx[0][0] + f[1] * (dx[0][1] - dx[0][0]), gx1 = dx[1][0] + f[1] * (dx[1][1] - dx[1][0]);
  distance = y0 + f[2] * (y1 - y0);
  gradient.x = (gx0 + f[2] * (gx1 - gx0)) * inv_cell_;
  gradient.y = ((x0[0][1] - x0[0][0]) + f[2] * ((x0[1][1] - x0[1][0]) - (x0[0][1] - x0[0][0]))) * inv_cell_;
  gradient.z = (y1 - y0) * inv_cell_;
  return true;
}

bool WallField::project(Vec3& pos, Vec3& vel) const {
  real d;
  Vec3 g;
  if (!sample(pos, d, g) || d >= clearance_) return false;
  const real len = norm(g);
  if (!(len > 0)) return false;  // a flat spot of the sampled distance: no direction to leave by
  const Vec3 n = g / len;
  pos += n * ((clearance_ - d) / len);  // |gradient| < 1 inside a cell: the step that reaches the clearance
  const real vn = dot(vel, n);
  if (vn < 0) vel -= n * vn;
  return true;
}

}  // namespace dentsph
