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
  // Coarse to fine: the distance at every kBlock-th corner first (and the last along each axis),
  // then block by block. The distance changes by at most the distance moved, so a block whose
  // coarse corners all lie farther than the block's diagonal plus the clearance from the walls (on
  // one side) holds no point within the clearance: its corners are interpolated from the coarse
  // ones, on the same side and beyond the clearance, where project() does nothing with them (inside,
  // that deep, no paste gets: it is held at the clearance on the way). The others are sampled.
  const auto at = [&](int i, int j, int k) { return lo + Vec3{real(i) * cell, real(j) * cell, real(k) * cell}; };
  int m[3];  // coarse corners along each axis: fine corners 0, kBlock, 2 kBlock, ..., n - 1
  for (int a = 0; a < 3; ++a) m[a] = (n_[a] - 1 + kBlock - 1) / kBlock + 1;
  const auto fine = [&](int a, int c) { return std::min(c * kBlock, n_[a] - 1); };
  const std::size_t coarse_count = std::size_t(m[0]) * std::size_t(m[1]) * std::size_t(m[2]);
  std::vector<real> coarse(coarse_count);
#pragma omp parallel for schedule(dynamic)
  for (std::int64_t ck = 0; ck < m[2]; ++ck)
    for (int cj = 0; cj < m[1]; ++cj)
      for (int ci = 0; ci < m[0]; ++ci)
        coarse[(std::size_t(ck) * m[1] + cj) * m[0] + ci] = distance(at(fine(0, ci), fine(1, cj), fine(2, int(ck))));
  const real margin = real(kBlock) * cell * std::sqrt(real(3)) + clearance;
  const int nb[3] = {m[0] - 1, m[1] - 1, m[2] - 1};  // blocks along each axis (n >= 2 corners: m >= 2)
  const std::int64_t blocks = std::int64_t(nb[0]) * nb[1] * nb[2];
#pragma omp parallel for schedule(dynamic)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const int c0[3] = {int(b % nb[0]), int((b / nb[0]) % nb[1]), int(b / (std::int64_t(nb[0]) * nb[1]))};
    int c1[3], f0[3], f1[3];
    for (int a = 0; a < 3; ++a) {
      c1[a] = c0[a] + 1;
      f0[a] = fine(a, c0[a]);
      f1[a] = fine(a, c1[a]);
    }
    real v[2][2][2];
    bool far_out = true, far_in = true;
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
          v[z][y][x] = coarse[(std::size_t(z ? c1[2] : c0[2]) * m[1] + (y ? c1[1] : c0[1])) * m[0] + (x ? c1[0] : c0[0])];
          far_out = far_out && v[z][y][x] > margin;
          far_in = far_in && v[z][y][x] < -margin;
        }
    // The block's corners: from its low corner up to, but not including, the next block's (the
    // last block along an axis takes the grid's last corner too).
    int e[3];
    for (int a = 0; a < 3; ++a) e[a] = c1[a] == m[a] - 1 ? f1[a] + 1 : f1[a];
    for (int k = f0[2]; k < e[2]; ++k)
      for (int j = f0[1]; j < e[1]; ++j)
        for (int i = f0[0]; i < e[0]; ++i) {
          real d;
          if (far_out || far_in) {
            const int g[3] = {i, j, k};
            real t[3];
            for (int a = 0; a < 3; ++a) t[a] = real(g[a] - f0[a]) / real(f1[a] - f0[a]);
            const real x00 = v[0][0][0] + (v[0][0][1] - v[0][0][0]) * t[0], x01 = v[0][1][0] + (v[0][1][1] - v[0][1][0]) * t[0];
            const real x10 = v[1][0][0] + (v[1][0][1] - v[1][0][0]) * t[0], x11 = v[1][1][0] + (v[1][1][1] - v[1][1][0]) * t[0];
            const real y0 = x00 + (x01 - x00) * t[1], y1 = x10 + (x11 - x10) * t[1];
            d = y0 + (y1 - y0) * t[2];
          } else {
            d = distance(at(i, j, k));
          }
          phi_[(std::size_t(k) * n_[1] + j) * n_[0] + i] = float(d);
        }
  }
}

bool WallField::sample(const Vec3& p, real& distance, Vec3& gradient) const {
  return sample_grid(phi_, n_, origin_, inv_cell_, p, distance, gradient);
}

bool sample_grid(std::span<const float> phi, const int n[3], const Vec3& origin, real inv_cell, const Vec3& p,
                 real& distance, Vec3& gradient) {
  const real g[3] = {(p.x - origin.x) * inv_cell, (p.y - origin.y) * inv_cell, (p.z - origin.z) * inv_cell};
  int c[3];
  real f[3];
  for (int a = 0; a < 3; ++a) {
    if (!(g[a] >= 0) || !(g[a] <= real(n[a] - 1))) return false;  // outside, or not a number
    c[a] = std::min(int(g[a]), n[a] - 2);
    f[a] = g[a] - real(c[a]);
  }
  const std::size_t sx = 1, sy = std::size_t(n[0]), sz = sy * std::size_t(n[1]);
  const std::size_t base = std::size_t(c[2]) * sz + std::size_t(c[1]) * sy + std::size_t(c[0]);
  real v[2][2][2];
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) v[k][j][i] = real(phi[base + k * sz + j * sy + i * sx]);
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
  gradient.x = (gx0 + f[2] * (gx1 - gx0)) * inv_cell;
  gradient.y = ((x0[0][1] - x0[0][0]) + f[2] * ((x0[1][1] - x0[1][0]) - (x0[0][1] - x0[0][0]))) * inv_cell;
  gradient.z = (y1 - y0) * inv_cell;
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
