// find_voids(): a flood fill from the box's faces and the tool marks the open empty space, then
// each remaining empty component is walked once. Iterative (an explicit stack), so a large empty
// region cannot overflow the call stack.
#include "assess/voids.hpp"

#include <algorithm>

namespace dentsph::assess {

namespace {

constexpr std::uint8_t kSeen = 2;

// Marks every empty voxel 6-connected to those on `stack` as seen; returns how many cavity
// voxels it marked (the ones on the stack included) and the sum of their indices.
Voids::Region flood(const VoxelGrid& g, std::vector<std::uint8_t>& mark,
                    std::vector<std::uint32_t>& stack) {
  const std::size_t sx = 1, sy = std::size_t(g.n[0]), sz = sy * std::size_t(g.n[1]);
  Voids::Region cavity;
  while (!stack.empty()) {
    const std::uint32_t v = stack.back();
    stack.pop_back();
    const int i = int(v % sy), j = int((v / sy) % std::size_t(g.n[1])), k = int(v / sz);
    if ((g.cell[v] & kClassMask) == kCavity) {
      ++cavity.cavity_voxels;
      cavity.i += i;
      cavity.j += j;
      cavity.k += k;
    }
    auto visit = [&](bool inside, std::size_t u) {
      if (inside && mark[u] == kEmpty) {
        mark[u] = kSeen;
        stack.push_back(std::uint32_t(u));
      }
    };
    visit(i > 0, v - sx);
    visit(i + 1 < g.n[0], v + sx);
    visit(j > 0, v - sy);
    visit(j + 1 < g.n[1], v + sy);
    visit(k > 0, v - sz);
    visit(k + 1 < g.n[2], v + sz);
  }
  return cavity;
}

}  // namespace

Voids find_voids(const VoxelGrid& g, std::vector<std::uint8_t>& mark,
                 std::uint32_t min_cavity_voxels) {
  std::vector<std::uint32_t> stack;
  auto seed = [&](int i, int j, int k) {
    const std::size_t v = g.index(i, j, k);
    if (mark[v] == kEmpty) {
      mark[v] = kSeen;
      stack.push_back(std::uint32_t(v));
    }
  };
  // The open space: everything empty that reaches a face of the box or the tool.
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::size_t v = g.index(i, j, k);
        const bool face =
            i == 0 || j == 0 || k == 0 || i == g.n[0] - 1 || j == g.n[1] - 1 || k == g.n[2] - 1;
        const bool tool = mark[v] == kOpen;
        if (tool) mark[v] = kEmpty;  // seeded below like an empty voxel on a face
        if (face || tool) seed(i, j, k);
      }
  flood(g, mark, stack);

  Voids out;
  const std::uint32_t min_voxels = std::max<std::uint32_t>(1, min_cavity_voxels);
  for (std::size_t v = 0; v < mark.size(); ++v) {
    if (mark[v] != kEmpty) continue;
    mark[v] = kSeen;
    stack.push_back(std::uint32_t(v));
    Voids::Region region = flood(g, mark, stack);
    const std::uint32_t cavity = region.cavity_voxels;
    if (cavity < min_voxels) {
      out.pores += cavity > 0;
      out.pore_cavity_voxels += cavity;
      continue;
    }
    ++out.count;
    out.cavity_voxels += cavity;
    out.largest = std::max(out.largest, cavity);
    region.i /= cavity;
    region.j /= cavity;
    region.k /= cavity;
    out.regions.push_back(region);
  }
  return out;
}

}  // namespace dentsph::assess
