// Bond updates outside the force pass: the boundary particles' lists (the force pass skips
// boundary particles), and the all-pairs reference. Moving particles update their own lists
// inside the force pass, from the distances it computes anyway (forces.cpp).
#include "bonds/hysteresis.hpp"

#include "step/grid.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void update_boundary_bonds(const Model& model, State& s, int threads) {
  const std::int64_t n = s.size();
  bonds::Events total;
#pragma omp parallel num_threads(threads)
  {
    bonds::Events ev;
#pragma omp for schedule(static) nowait
    for (std::int64_t k = 0; k < n; ++k) {
      const auto i = std::uint32_t(k);
      if (s.role[i] != Role::boundary) continue;
      bonds::break_stretched(model, s, i, ev);
      // A boundary particle bonds only to material: it looks at moving particles alone.
      grid::for_each_in_neighbourhood(model.grid, s.grid, s.pos[i], grid::Visit::moving, [&](std::uint32_t j) {
        bonds::try_form(model, s, i, j, norm2(s.pos[i] - s.pos[j]), ev);
      });
    }
#pragma omp critical(dentsph_bond_events)
    total += ev;
  }
  bonds::record(s, total);
}

void update_bonds_all_pairs(const Model& model, State& s) {
  bonds::Events ev;
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    bonds::break_stretched(model, s, i, ev);
    for (std::uint32_t j = 0; j < n; ++j) bonds::try_form(model, s, i, j, norm2(s.pos[i] - s.pos[j]), ev);
  }
  bonds::record(s, ev);
}

}  // namespace dentsph::stages
