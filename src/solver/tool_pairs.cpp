// The iisph solver's tool neighbours, found every step. The tool is driven by the hand: in the
// built-in procedure it moves up to 0.06 mm a step (a tenth of h) at the iisph solver's dt, more
// than the neighbour lists' skin allows between rebuilds, so that with the tool in the lists they
// were rebuilt every other step, and a rebuild's search of the grid costs as much as the rest of
// the pair pass. The tool's few particles are left out of the lists and of the rebuild's criterion
// instead (stages::lists_need_rebuild), and each step this finds:
//  - each tool particle's neighbours within h: the material and the boundary from a search of the
//    grid of the last rebuild, at their positions now (each has moved less than skin / 2 from where
//    it was sorted, and the cells are h + skin wide, so the 27 cells around the tool particle hold
//    every one within h), the other tool particles from all of them;
//  - the same pairs from the other side: each material or boundary particle's tool neighbours, in
//    the order of the tool particles (link_start, link_tool), for its row (pairs.cpp).
// The same on every thread count: each tool particle writes its own list, the transposition is serial.
#include <algorithm>

#include "solver/iisph.hpp"
#include "step/grid.hpp"

namespace dentsph::iisph {

std::uint64_t find_tool_pairs(const Model& model, State& s, IisphScratch& x, int threads) {
  const std::int64_t tools = std::int64_t(x.tools.size());
  const real h2 = model.kernel.h2;
  constexpr std::uint32_t cap = IisphScratch::kToolStride - 1;  // one scratch slot
  std::uint64_t overflow = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : overflow)
  for (std::int64_t k = 0; k < tools; ++k) {
    const std::uint32_t t = x.tools[k];
    std::uint32_t* list = x.tool_list.data() + std::size_t(k) * IisphScratch::kToolStride;
    std::uint32_t count = 0;
    const Vec3 pt = s.pos[t];
    auto consider = [&](std::uint32_t j, bool wanted) {
      const std::uint32_t within = (norm2(pt - s.pos[j]) < h2) & wanted;
      list[count < cap ? count : cap] = j;
      count += within;
    };
    grid::for_each_in_neighbourhood(model.grid, s.grid, pt, grid::Visit::all,
                             [&](std::uint32_t j) { consider(j, s.role[j] != Role::tool); });
    for (const std::uint32_t u : x.tools) consider(u, u != t);
    overflow += count > cap ? count - cap : 0;
    x.tool_count[k] = std::uint16_t(std::min(count, cap));
  }
  // Transposed: count each particle's tool neighbours, their starts, then the tool particles in order.
  std::fill(x.link_start.begin(), x.link_start.end(), 0u);
  auto each_link = [&](auto&& fn) {
    for (std::int64_t k = 0; k < tools; ++k) {
      const std::uint32_t* list = x.tool_list.data() + std::size_t(k) * IisphScratch::kToolStride;
      for (std::uint32_t q = 0; q < x.tool_count[k]; ++q)
        if (s.role[list[q]] != Role::tool) fn(list[q], x.tools[k]);
    }
  };
  each_link([&](std::uint32_t j, std::uint32_t) { ++x.link_start[j + 1]; });
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    x.link_start[i + 1] += x.link_start[i];
    x.link_fill[i] = x.link_start[i];
  }
  each_link([&](std::uint32_t j, std::uint32_t t) { x.link_tool[x.link_fill[j]++] = t; });
  return overflow;
}

}  // namespace dentsph::iisph
