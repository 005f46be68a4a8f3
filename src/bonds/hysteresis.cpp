// Bond hysteresis of the all-pairs reference, before its density pass. The grid step updates each
// moving particle's list inside the force pass, from the distances it computes anyway (forces.cpp).
#include "bonds/hysteresis.hpp"

#include "step/stages.hpp"

namespace dentsph::stages {

void update_bonds_all_pairs(const Model& model, State& s) {
  bonds::Events ev;
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    if (s.role[i] == Role::boundary) continue;  // keeps no list (hysteresis.hpp)
    bonds::break_stretched(model, s, i, ev);
    for (std::uint32_t j = 0; j < n; ++j) bonds::try_form(model, s, i, j, norm2(s.pos[i] - s.pos[j]), ev);
  }
  bonds::record(s, ev);
}

}  // namespace dentsph::stages
