// The gel transition and shrinkage (docs/model.md, "Curing"). Past its gel point paste no longer
// flows: the particle becomes a static boundary particle where it is (its velocity zeroed), so the
// step treats it as wall: it gets a static density, keeps no bond list (a bond from moving paste
// to it lives in the moving particle's list and stays; bonds to the instrument, which never bonds
// to a wall, and between two set particles are dropped, not counted as broken), and the paste
// placed on it later bonds to it. Then, as its conversion rises, it shrinks with its increment:
// each rigid particle's place is its place at gelation scaled towards the mass centroid of its
// increment's rigid particles by the cube root of the volume left since the gel point,
// (1 - S alpha / alpha_max) / (1 - S alpha_gel / alpha_max): free shrinkage of the set part, mass
// kept. (A particle found past the gel point by a pass shrinks at once by what it passed it by.)
#include <algorithm>
#include <cmath>

#include "dentsph/cure.hpp"

namespace dentsph {

namespace {

// Turns moving paste particle i rigid.
void make_rigid(State& s, std::uint32_t i) {
  const std::uint32_t id = s.id[i];
  BondStore& bonds = s.bonds;
  for (int b = bonds.count(id) - 1; b >= 0; --b) {
    const std::uint32_t other = bonds.partner(id, b);
    if (s.role[s.index_of_id[other]] == Role::tool)
      for (int k = bonds.count(other) - 1; k >= 0; --k)
        if (bonds.partner(other, k) == id) bonds.remove_at(other, k);
    bonds.remove_at(id, b);
  }
  s.role[i] = Role::boundary;
  s.vel[i] = {};
  s.cure.rigid[id] = 1;
  s.cure.gel_pos[id] = s.pos[i];
}

// The volume fraction left of paste at conversion alpha.
real volume_left(const CureMaterial& m, real alpha) {
  return 1 - m.shrinkage * std::clamp(alpha / m.alpha_max, real(0), real(1));
}

}  // namespace

CureUpdate apply_cure_transition(const CureModel& cm, State& s) {
  CureState& c = s.cure;
  const CureMaterial& m = cm.paste;
  CureUpdate up;
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t id = s.id[i];
    if (c.curable[id] && s.role[i] == Role::material && c.alpha[id] >= m.alpha_gel && is_finite(s.pos[i])) {
      make_rigid(s, i);
      ++up.set;
    }
  }
  // Shrinkage of the rigid part of each increment about its mass centroid at gelation.
  if (m.shrinkage > 0) {
    const std::size_t incs = std::size_t(c.increments) + 1;
    std::vector<Vec3>& sum = c.increment_sum;
    std::vector<real>& mass = c.increment_mass;
    sum.assign(incs, Vec3{});  // no allocation once sized
    mass.assign(incs, 0);
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t id = s.id[i];
      if (!c.rigid[id]) continue;
      sum[c.increment[id]] += s.mass[i] * c.gel_pos[id];
      mass[c.increment[id]] += s.mass[i];
    }
    real moved2 = 0;
    auto target = [&](std::uint32_t i) {
      const std::uint32_t id = s.id[i];
      const Vec3 centre = sum[c.increment[id]] / mass[c.increment[id]];
      const real scale = std::cbrt(volume_left(m, c.alpha[id]) / volume_left(m, m.alpha_gel));
      return centre + (c.gel_pos[id] - centre) * scale;
    };
    for (std::uint32_t i = 0; i < n; ++i)
      if (c.rigid[s.id[i]]) moved2 = std::max(moved2, norm2(target(i) - s.pos[i]));
    if (moved2 > cm.shrink_tolerance * cm.shrink_tolerance) {
      for (std::uint32_t i = 0; i < n; ++i)
        if (c.rigid[s.id[i]]) s.pos[i] = target(i);
      up.moved = true;
    }
  }
  if (up.set > 0 || up.moved) {
    // The walls changed: the next step sorts anew and recomputes the static density.
    s.rho_static_valid = false;
    s.grid.lists_valid = false;
  }
  return up;
}

}  // namespace dentsph
