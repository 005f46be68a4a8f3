// The assessment's voxel grid: a box in the tooth frame around the cavity and the band above
// it, each voxel classified once as tooth, cavity or air, with what assess() needs to judge the
// particles and the colour field without querying the tooth again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dentsph/tooth.hpp"

namespace dentsph::assess {

// Low two bits of a voxel: what its centre lies in.
enum VoxelClass : std::uint8_t { kAir = 0, kCavity = 1, kTooth = 2 };
constexpr std::uint8_t kClassMask = 3;
// Leak state of a particle anywhere in the voxel (prepared distance against -leak_depth):
// certainly deeper (kDeep), uncertain (kUnsure: query the tooth), otherwise certainly not.
constexpr std::uint8_t kDeep = 4, kUnsure = 8;

// A cavity or air voxel nearer the prepared surface than the wall standoff: its colour field
// is read at `at` (frame coordinates, m), the point the standoff away from the surface.
struct Probe {
  std::uint32_t voxel;
  Vec3 at;
};

struct VoxelGrid {
  Vec3 origin;    // m, frame coordinates of the corner of voxel (0, 0, 0)
  real edge = 0;  // m
  int n[3] = {0, 0, 0};
  std::vector<std::uint8_t> cell;  // [n0 n1 n2], x fastest: class | leak bits
  std::vector<Probe> probes;       // ascending voxel
  std::uint32_t cavity_voxels = 0, air_voxels = 0;

  std::size_t size() const { return std::size_t(n[0]) * n[1] * n[2]; }
  std::size_t index(int i, int j, int k) const {
    return (std::size_t(k) * n[1] + std::size_t(j)) * n[0] + std::size_t(i);
  }
  Vec3 centre(int i, int j, int k) const {
    return origin + Vec3{(i + 0.5) * edge, (j + 0.5) * edge, (k + 0.5) * edge};
  }
};

// Voxels of `edge` covering `box` (frame coordinates, m; snapped outwards to multiples of
// `edge` from the frame origin). `standoff` and `leak_depth` as in AssessParams.
VoxelGrid voxelise(const PreparedTooth& tooth, const Bounds& box, real edge, real standoff,
                   real leak_depth);

}  // namespace dentsph::assess
