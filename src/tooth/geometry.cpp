// Eigen decomposition of a symmetric 3x3 matrix (see geometry.hpp).
#include "tooth/geometry.hpp"

#include <algorithm>
#include <numeric>

namespace dentsph::tooth {

Eigen3 symmetric_eigen(Mat3 a) {
  // Cyclic Jacobi (Numerical Recipes 11.1): each rotation zeroes one off-diagonal entry; the
  // off-diagonal sum falls quadratically, so a handful of sweeps reach round-off.
  Mat3 v{};
  for (int k = 0; k < 3; ++k) v[k][k] = 1;
  const real scale = std::fabs(a[0][0]) + std::fabs(a[1][1]) + std::fabs(a[2][2]);
  for (int sweep = 0; sweep < 64; ++sweep) {
    const real off = std::fabs(a[0][1]) + std::fabs(a[0][2]) + std::fabs(a[1][2]);
    if (off <= 1e-15 * scale || off == 0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0) continue;
        const real theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const real t = (theta >= 0 ? 1 : -1) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const real c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {
          const real akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const real apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const real vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  std::array<int, 3> order;
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] > a[j][j]; });
  Eigen3 e;
  for (int i = 0; i < 3; ++i) {
    const int k = order[i];
    e.values[i] = a[k][k];
    e.vectors[i] = normalized(Vec3{v[0][k], v[1][k], v[2][k]});
  }
  return e;
}

}  // namespace dentsph::tooth
