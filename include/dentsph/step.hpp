// One simulation step: the paper's six stages (MODEL.md, "One step").
#pragma once

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

// The grid step: cell keys, counting radix sort, reorder and cell ranges, bond hysteresis,
// density, pressure, forces over the 27 neighbouring cells, semi-implicit Euler; then the tool
// wrench. The tool moves to state.tool_pose. Allocation-free once particles are added.
void step(const Model& model, State& state);

// The all-pairs reference step (the paper's "less efficient algorithm"): the same physics with
// every pair visited, no grid and no reordering. Every faster path is tested against it.
void step_all_pairs(const Model& model, State& state);

// Time-step limits of MODEL.md, "Stability", in seconds.
struct StabilityLimits {
  real acoustic = 0;  // lambda h / sqrt(max Kp)
  real viscous = 0;   // 0.125 h^2 min(rho0 / mu)
  real force = 0;     // 0.25 sqrt(h / max|a|), from the last step (infinite before any)
  real sound_speed = 0;  // m/s, c = sqrt(max Kp); material moving at many times c has exploded
};
StabilityLimits stability_limits(const Model& model, const State& state);

}  // namespace dentsph
