// Gathers one particle's view for the pair terms.
#pragma once

#include "dentsph/state.hpp"
#include "physics/pair_terms.hpp"

namespace dentsph::stages {

inline pair::Side side_of(const State& s, std::uint32_t i) {
  return {s.pos[i], s.vel[i], s.volume[i], s.pressure[i], s.mu[i], s.Ka[i]};
}

// The same view from the records of the grid step's density pass (GridIndex::pair_data), through a
// pointer taken once: in a loop that may call out (bond insertion), a local needs no reloading
// where the State's vectors would.
struct Sides {
  const PairData* data;
  explicit Sides(const State& s) : data(s.grid.pair_data.data()) {}
  const Vec3& pos(std::uint32_t i) const { return data[i].pos; }
  pair::Side operator[](std::uint32_t i) const {
    const PairData& d = data[i];
    return {d.pos, d.vel, d.vol, d.pressure, d.mu, d.Ka};
  }
};

}  // namespace dentsph::stages
