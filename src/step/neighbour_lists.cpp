// Neighbour lists with a skin (Verlet lists): built with radius h + skin when the particles are
// sorted, and kept while no particle has moved more than skin / 2 since, so that every pair
// within h is still in them (two particles closing in at most skin between them). Between
// rebuilds the step skips the broad phase, the sort and the reorder.
#include <algorithm>

#include "step/stages.hpp"

namespace dentsph::stages {

bool lists_need_rebuild(const Model& model, const State& s, int threads, bool tool_listed) {
  // GridIndex::keep_lists is set where the state was made with a skin (neighbour_skin > 0).
  const real skin = model.neighbour_skin;
  if (!s.grid.keep_lists || !s.grid.lists_valid) return true;
  const real limit2 = 0.25 * skin * skin;
  const std::int64_t n = s.size();
  const Vec3* pos = s.pos.data();
  const Vec3* built = s.grid.pos_at_build.data();
  const Role* role = s.role.data();
  real moved2 = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : moved2)
  for (std::int64_t i = 0; i < n; ++i) {
    const bool counted = tool_listed || role[i] != Role::tool;
    moved2 = std::max(moved2, counted ? norm2(pos[i] - built[i]) : real(0));
  }
  return !(moved2 <= limit2);  // a non-finite position rebuilds too
}

void remember_build_positions(State& s, int threads) {
  if (!s.grid.keep_lists) return;  // every step rebuilds: nothing to remember
  const std::int64_t n = s.size();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) s.grid.pos_at_build[i] = s.pos[i];
  s.grid.lists_valid = true;
}

}  // namespace dentsph::stages
