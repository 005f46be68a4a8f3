// Bond hysteresis (MODEL.md, "Adhesion hysteresis"): a pair bonds when r < A, stays bonded while
// r <= B, and unbonds when r > B. Each particle updates only its own list, from the same squared
// distance its partner sees (|r_i - r_j|^2 is bit-identical both ways), so the decision is
// symmetric and the per-particle loop is free of write conflicts. Each event is counted once,
// by the side with the smaller id.
#include "physics/pair_terms.hpp"
#include "step/grid.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

namespace {

// Removes the partners of particle i that are now beyond B.
void break_stretched(const Model& model, State& s, std::uint32_t i) {
  const real B2 = model.adhesion.B * model.adhesion.B;
  const std::uint32_t id = s.id[i];
  for (int b = s.bonds.count(id) - 1; b >= 0; --b) {
    const std::uint32_t other = s.bonds.partner(id, b);
    if (norm2(s.pos[i] - s.pos[s.index_of_id[other]]) > B2) {
      s.bonds.remove_at(id, b);
      if (id < other) ++s.bonds.counters.broken;
    }
  }
}

// Bonds particle i to j if they are closer than A, may bond, and are not bonded yet.
inline void try_form(const Model& model, State& s, std::uint32_t i, std::uint32_t j) {
  if (j == i) return;
  if (!(norm2(s.pos[i] - s.pos[j]) < model.adhesion.A * model.adhesion.A)) return;
  if (!pair::can_bond(s.role[i], s.role[j], s.Ka[i], s.Ka[j])) return;
  const std::uint32_t a = s.id[i], b = s.id[j];
  if (s.bonds.has(a, b)) return;
  if (s.bonds.add(a, b) && a < b) ++s.bonds.counters.formed;
}

}  // namespace

void update_bonds(const Model& model, State& s) {
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    break_stretched(model, s, i);
    // A < h <= cell size: every pair closer than A is in the 27 cells. A boundary particle
    // bonds only to material, so it looks at moving particles alone.
    const grid::Visit visit = s.role[i] == Role::boundary ? grid::Visit::moving : grid::Visit::all;
    grid::for_each_in_neighbourhood(model.grid, s.grid, s.pos[i], visit,
                                    [&](std::uint32_t j) { try_form(model, s, i, j); });
  }
}

void update_bonds_all_pairs(const Model& model, State& s) {
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    break_stretched(model, s, i);
    for (std::uint32_t j = 0; j < n; ++j) try_form(model, s, i, j);
  }
}

}  // namespace dentsph::stages
