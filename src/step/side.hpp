// Gathers one particle's view for the pair terms.
#pragma once

#include "dentsph/state.hpp"
#include "physics/pair_terms.hpp"

namespace dentsph::stages {

inline pair::Side side_of(const State& s, std::uint32_t i) {
  return {s.pos[i], s.vel[i], s.volume[i], s.pressure[i], s.mu[i], s.Ka[i]};
}

}  // namespace dentsph::stages
