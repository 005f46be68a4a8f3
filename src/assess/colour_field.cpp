// splat() and sample(): the colour field of assess/colour_field.hpp.
#include "assess/colour_field.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace dentsph::assess {

namespace {

// Voxel centres within two spacings on each axis: at most 2 * 2 * 8 + 1 for voxels of at least
// spacing / 8 (AssessParams refuses smaller).
constexpr int kMaxTaps = 40;

}  // namespace

void splat(const VoxelGrid& g, real spacing, const std::vector<Vec3>& points,
           std::vector<float>& field) {
  const real reach = 2 * spacing / g.edge;  // support radius, in voxels
  const real to_knots = g.edge / spacing;
  for (const Vec3& p : points) {
    if (!is_finite(p)) continue;
    int first[3], count[3];
    std::array<float, kMaxTaps> w[3];
    bool outside = false;
    for (int d = 0; d < 3; ++d) {
      // Voxel coordinate u: voxel i's centre is at u = i.
      const real u = (p[d] - g.origin[d]) / g.edge - 0.5;
      // Tested before the conversions to int, which a far point would overflow.
      if (!(u > -reach - 1 && u < g.n[d] + reach)) {
        outside = true;
        break;
      }
      const int a = std::max(0, int(std::ceil(u - reach))),
                b = std::min(g.n[d] - 1, int(std::floor(u + reach)));
      if (b < a) {
        outside = true;
        break;
      }
      first[d] = a;
      count[d] = std::min(b - a + 1, kMaxTaps);
      for (int q = 0; q < count[d]; ++q) w[d][q] = float(cubic_bspline((a + q - u) * to_knots));
    }
    if (outside) continue;
    for (int k = 0; k < count[2]; ++k)
      for (int j = 0; j < count[1]; ++j) {
        const float wjk = w[1][j] * w[2][k];
        float* row = field.data() + g.index(first[0], first[1] + j, first[2] + k);
        for (int i = 0; i < count[0]; ++i) row[i] += wjk * w[0][i];
      }
  }
}

real sample(const VoxelGrid& g, const std::vector<float>& field, const Vec3& at) {
  int i0[3];
  real t[3];
  for (int d = 0; d < 3; ++d) {
    const real u = std::clamp((at[d] - g.origin[d]) / g.edge - 0.5, real(0), real(g.n[d] - 1));
    i0[d] = std::min(int(u), std::max(0, g.n[d] - 2));
    t[d] = g.n[d] > 1 ? u - i0[d] : 0;
  }
  real sum = 0;
  for (int q = 0; q < 8; ++q) {
    real w = 1;
    int c[3];
    for (int d = 0; d < 3; ++d) {
      const bool up = (q >> d) & 1;
      c[d] = std::min(i0[d] + up, g.n[d] - 1);
      w *= up ? t[d] : 1 - t[d];
    }
    sum += w * field[g.index(c[0], c[1], c[2])];
  }
  return sum;
}

}  // namespace dentsph::assess
