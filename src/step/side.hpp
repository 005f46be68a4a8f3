// One particle's view for the pair terms from the records of the grid step's density pass.
#pragma once

#include "dentsph/state.hpp"
#include "physics/pair_terms.hpp"

namespace dentsph::stages {

// A particle's pair::Side (pair::side_of of the State) from the records of the grid step's density pass (GridIndex::pair_data), through a
// pointer taken once: in a loop that may call out (bond insertion), a local needs no reloading
// where the State's vectors would.
struct Sides {
  const PairData* data;
  explicit Sides(const State& s) : data(s.grid.pair_data.data()) {}
  const Vec3& pos(std::uint32_t i) const { return data[i].pos; }
  const pair::Side& operator[](std::uint32_t i) const { return data[i]; }
};

}  // namespace dentsph::stages
