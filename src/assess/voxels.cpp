// voxelise(): classifies every voxel of the box by its centre, querying the tooth only where
// the answer can change inside a block.
//
// Both distances involved are 1-Lipschitz: the original tooth's signed distance t and the
// prepared tooth's f = max(t, -cavity distance) (exact inside the prepared tooth, a lower bound
// outside; still 1-Lipschitz as the maximum of two). So one query at a block's centre settles
// the whole block when no level set that matters (t = 0, cavity = 0, f = 0, f = standoff,
// f = -leak_depth) comes within the block's half-diagonal; otherwise the block is split in
// eight, down to single voxels. The default scene's box holds about 150,000 voxels, and only
// those near the surfaces are queried one by one.
#include "assess/voxels.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace dentsph::assess {

namespace {

constexpr int kTopBlock = 16;  // voxels along each side of the blocks handed to threads

struct Classifier {
  const PreparedTooth& tooth;
  VoxelGrid& g;
  real standoff, leak, half_diag;  // m; half_diag: of one voxel
  std::vector<Probe>& probes;      // this thread's

  Vec3 local_dir(const Vec3& w) const {
    const ToothFrame& f = tooth.frame();
    return {dot(w, f.x), dot(w, f.y), dot(w, f.z)};
  }

  // One voxel, from the queries at its centre.
  void voxel(int i, int j, int k, const Vec3& at, const SurfacePoint& t, const SurfacePoint& c) {
    const real f = std::max(t.distance, -c.distance);
    std::uint8_t v = f < 0 ? kTooth : (t.distance < 0 ? kCavity : kAir);
    if (f < -leak - half_diag)
      v |= kDeep;
    else if (f <= -leak + half_diag)
      v |= kUnsure;
    const std::size_t idx = g.index(i, j, k);
    g.cell[idx] = v;
    if ((v & kClassMask) != kTooth && f < standoff) {
      // The prepared surface's outward normal is the one of whichever distance is the larger.
      const Vec3 n = local_dir(t.distance >= -c.distance ? t.normal : -c.normal);
      probes.push_back({std::uint32_t(idx), at + n * (standoff - f)});
    }
  }

  void block(const int lo[3], const int hi[3]) {
    const int m[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    // The mean of the voxel centres, and the largest distance from it to one of them.
    const Vec3 at = g.origin + Vec3{0.5 * (lo[0] + hi[0]) * g.edge, 0.5 * (lo[1] + hi[1]) * g.edge,
                                    0.5 * (lo[2] + hi[2]) * g.edge};
    const real r = 0.5 * g.edge *
                   std::sqrt(real((m[0] - 1) * (m[0] - 1) + (m[1] - 1) * (m[1] - 1) +
                                  (m[2] - 1) * (m[2] - 1)));
    const Vec3 w = tooth.frame().to_world(at);
    const SurfacePoint t = tooth.tooth().query(w);
    const SurfacePoint c = tooth.cavity_distance(w);
    if (m[0] == 1 && m[1] == 1 && m[2] == 1) return voxel(lo[0], lo[1], lo[2], at, t, c);

    const real f = std::max(t.distance, -c.distance);
    const bool one_class = std::abs(t.distance) > r && (t.distance > 0 || std::abs(c.distance) > r);
    const bool deep = f + r < -leak - half_diag;
    const bool clear = f - r > -leak + half_diag;
    const bool settled = (f - r > standoff && clear) || (f + r < 0 && (deep || clear));
    if (one_class && settled) {
      std::uint8_t v = f < 0 ? kTooth : (t.distance < 0 ? kCavity : kAir);
      if (deep) v |= kDeep;
      for (int k = lo[2]; k < hi[2]; ++k)
        for (int j = lo[1]; j < hi[1]; ++j)
          std::fill_n(g.cell.begin() + std::ptrdiff_t(g.index(lo[0], j, k)), m[0], v);
      return;
    }
    // Split every axis longer than one voxel in two.
    for (int q = 0; q < 8; ++q) {
      int a[3], b[3];
      bool empty = false;
      for (int d = 0; d < 3; ++d) {
        const int mid = lo[d] + m[d] / 2;
        const bool upper = (q >> d) & 1;
        if (m[d] == 1 && upper) empty = true;
        a[d] = m[d] == 1 ? lo[d] : (upper ? mid : lo[d]);
        b[d] = m[d] == 1 ? hi[d] : (upper ? hi[d] : mid);
      }
      if (!empty) block(a, b);
    }
  }
};

}  // namespace

VoxelGrid voxelise(const PreparedTooth& tooth, const Bounds& box, real edge, real standoff,
                   real leak_depth) {
  VoxelGrid g;
  g.edge = edge;
  int lo[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = int(std::floor(box.min[d] / edge));
    g.n[d] = std::max(1, int(std::ceil(box.max[d] / edge)) - lo[d]);
  }
  g.origin = Vec3{lo[0] * edge, lo[1] * edge, lo[2] * edge};
  g.cell.assign(g.size(), kAir);

  std::vector<std::array<int, 3>> blocks;
  for (int k = 0; k < g.n[2]; k += kTopBlock)
    for (int j = 0; j < g.n[1]; j += kTopBlock)
      for (int i = 0; i < g.n[0]; i += kTopBlock) blocks.push_back({i, j, k});

  const real half_diag = 0.5 * std::sqrt(3.0) * edge;
  std::vector<std::vector<Probe>> found(static_cast<std::size_t>(omp_get_max_threads()));
#pragma omp parallel
  {
    std::vector<Probe>& mine = found[std::size_t(omp_get_thread_num())];
    Classifier c{tooth, g, standoff, leak_depth, half_diag, mine};
#pragma omp for schedule(dynamic, 1)
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const int a[3] = {blocks[b][0], blocks[b][1], blocks[b][2]};
      const int e[3] = {std::min(a[0] + kTopBlock, g.n[0]), std::min(a[1] + kTopBlock, g.n[1]),
                        std::min(a[2] + kTopBlock, g.n[2])};
      c.block(a, e);
    }
  }
  for (auto& f : found) g.probes.insert(g.probes.end(), f.begin(), f.end());
  // Ascending voxel, so the result does not depend on which thread found what.
  std::sort(g.probes.begin(), g.probes.end(),
            [](const Probe& a, const Probe& b) { return a.voxel < b.voxel; });
  for (const std::uint8_t v : g.cell) {
    g.cavity_voxels += (v & kClassMask) == kCavity;
    g.air_voxels += (v & kClassMask) == kAir;
  }
  return g;
}

}  // namespace dentsph::assess
