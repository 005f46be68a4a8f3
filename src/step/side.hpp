// Gathers one particle's view for the pair terms.
#pragma once

#include "dentsph/state.hpp"
#include "physics/pair_terms.hpp"

namespace dentsph::stages {

inline pair::Side side_of(const State& s, std::uint32_t i) {
  return {s.pos[i], s.vel[i], s.volume[i], s.pressure[i], s.mu[i], s.Ka[i]};
}

// The same view from array pointers taken once: in a loop that may call out (bond insertion),
// locals need no reloading where the State's vectors would.
struct Sides {
  const Vec3 *pos, *vel;
  const real *vol, *pressure, *mu, *Ka;
  explicit Sides(const State& s)
      : pos(s.pos.data()), vel(s.vel.data()), vol(s.volume.data()), pressure(s.pressure.data()), mu(s.mu.data()),
        Ka(s.Ka.data()) {}
  pair::Side operator[](std::uint32_t i) const { return {pos[i], vel[i], vol[i], pressure[i], mu[i], Ka[i]}; }
};

}  // namespace dentsph::stages
