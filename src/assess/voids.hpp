// Enclosed empty regions: connected components (6-connectivity) of empty voxels that cannot be
// reached through empty voxels from the box's faces or from the tool.
#pragma once

#include <cstdint>
#include <vector>

#include "assess/voxels.hpp"

namespace dentsph::assess {

constexpr std::uint8_t kSolid = 0, kEmpty = 1, kOpen = 3;

struct Voids {
  int count = 0;                    // components holding at least min_cavity_voxels
  std::uint32_t cavity_voxels = 0;  // cavity voxels in them
  std::uint32_t largest = 0;        // cavity voxels in the largest
  // Each void: its cavity voxels and their mean voxel index (x, y, z), in the order found.
  struct Region {
    std::uint32_t cavity_voxels = 0;
    double i = 0, j = 0, k = 0;
  };
  std::vector<Region> regions;
  // Enclosed components holding some cavity voxels but fewer than min_cavity_voxels: porosity
  // below what the model resolves, counted apart.
  int pores = 0;
  std::uint32_t pore_cavity_voxels = 0;
};

// `mark` ([g.size()]): kSolid where a voxel is tooth or filled, kEmpty where it is cavity or
// air and not filled, kOpen where it is empty and taken by the tool (open space, like the box's
// faces: the tool reaches the outside through its handle). Used as scratch. A component is a void
// when it holds at least `min_cavity_voxels` (>= 1) cavity voxels; only those count in the volume
// (air voxels in it lie above the margin, in excess material that is carved away). A component
// with fewer (but some) cavity voxels is a pore.
Voids find_voids(const VoxelGrid& g, std::vector<std::uint8_t>& mark,
                 std::uint32_t min_cavity_voxels);

}  // namespace dentsph::assess
