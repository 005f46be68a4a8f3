// Bond hysteresis (docs/model.md, "Adhesion hysteresis"): a pair bonds when r < A, stays bonded while
// r <= B, and unbonds when r > B. Each particle updates only its own list, from the same squared
// distance its partner sees (|r_i - r_j|^2 is bit-identical both ways), so the decision is
// symmetric and a per-particle loop is free of write conflicts. Boundary particles keep no lists
// (they never move, so nothing of theirs reads one): a bond to a wall lives in the moving
// particle's list alone. Each event is counted once: by the side with the smaller id when both
// sides keep lists, by the moving side when the partner is a boundary particle. The caller adds
// the events to the store's counters.
#pragma once

#include <algorithm>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "physics/bond_rules.hpp"
#include "physics/pair_terms.hpp"

namespace dentsph::bonds {

struct Events {
  std::uint64_t formed = 0, broken = 0, overflowed = 0;
  Events& operator+=(const Events& o) {
    formed += o.formed, broken += o.broken, overflowed += o.overflowed;
    return *this;
  }
};

// Counts the break of the bond of moving particle i to j (once per pair).
inline void count_break(const State& s, std::uint32_t i, std::uint32_t j, Events& ev) {
  if (bond_rules::counts_event(s.id[i], s.id[j], s.role[j])) ++ev.broken;
}

// Removes the partners of moving particle i that are now beyond B.
inline void break_stretched(const Model& model, State& s, std::uint32_t i, Events& ev) {
  const bond_rules::Thresholds t = bond_rules::thresholds(model.adhesion);
  const std::uint32_t id = s.id[i];
  for (int b = s.bonds.count(id) - 1; b >= 0; --b) {
    const std::uint32_t j = s.index_of_id[s.bonds.partner(id, b)];
    if (bond_rules::stretched(norm2(s.pos[i] - s.pos[j]), t)) {
      count_break(s, i, j, ev);
      s.bonds.remove_at(id, b);
    }
  }
}

// Whether particles i and j may bond at all (bonded already or not): pair::can_bond of their roles
// and strengths.
inline bool can_bond(const State& s, std::uint32_t i, std::uint32_t j) {
  return pair::can_bond(s.role[i], s.role[j], s.Ka[i], s.Ka[j]);
}

// Whether moving particle i may bond to j, whose squared distance is r2: closer than A, and a
// pair that may bond at all (bonded already or not).
inline bool may_form(const Model& model, const State& s, std::uint32_t i, std::uint32_t j, real r2) {
  return bond_rules::may_form(i, j, r2, bond_rules::thresholds(model.adhesion), s.role[i], s.role[j], s.Ka[i], s.Ka[j]);
}

// Bonds moving particle i to j, known not to be bonded yet (counts the overflow of a full list).
inline void form(State& s, std::uint32_t i, std::uint32_t j, Events& ev) {
  const std::uint32_t a = s.id[i], b = s.id[j];
  if (!s.bonds.try_add(a, b))
    ++ev.overflowed;
  else if (bond_rules::counts_event(a, b, s.role[j]))
    ++ev.formed;
}

// Bonds moving particle i to j, whose squared distance is r2, if they are closer than A, may bond, and
// are not bonded yet: the all-pairs reference's rule, pair by pair. The grid step forms the bonds of
// each particle's close pairs at once, in the same order (form_bonds below).
inline void try_form(const Model& model, State& s, std::uint32_t i, std::uint32_t j, real r2, Events& ev) {
  if (!may_form(model, s, i, j, r2) || s.bonds.has(s.id[i], s.id[j])) return;
  form(s, i, j, ev);
}

// Bonds moving particle i to those of the n close pairs (j != i, r^2 < A^2, as the callers filter
// them) that may bond and are not bonded yet, in the order given (as bonds::try_form of the
// all-pairs step one by one would): the grid step's one way of forming bonds, from its lists and
// from its search of overflowed ones (src/step/forces.cpp), and the iisph solver's (src/solver).
// Which are bonded already is found in one pass over i's bond list per chunk, with loops of fixed
// length: a search per pair that stops at its partner mispredicted about once per pair.
inline void form_bonds(State& s, std::uint32_t i, const std::uint32_t* close, std::uint32_t n, bonds::Events& ev) {
  constexpr std::uint32_t chunk = GridIndex::kNeighbourStride;
  const std::uint32_t id = s.id[i];
  for (std::uint32_t c0 = 0; c0 < n; c0 += chunk) {
    const std::uint32_t m = std::min(chunk, n - c0);
    std::uint32_t close_id[chunk];
    std::uint8_t bonded[chunk];
    for (std::uint32_t c = 0; c < m; ++c) {
      close_id[c] = s.id[close[c0 + c]];
      bonded[c] = 0;
    }
    for (int b = 0; b < s.bonds.count(id); ++b) {
      const std::uint32_t partner = s.bonds.partner(id, b);
      for (std::uint32_t c = 0; c < m; ++c) bonded[c] |= close_id[c] == partner ? 1 : 0;
    }
    for (std::uint32_t c = 0; c < m; ++c)
      if (!bonded[c] && bonds::can_bond(s, i, close[c0 + c])) bonds::form(s, i, close[c0 + c], ev);
  }
}

inline void record(State& s, const Events& ev) {
  s.bonds.counters.formed += ev.formed;
  s.bonds.counters.broken += ev.broken;
  s.bonds.counters.overflowed += ev.overflowed;
}

}  // namespace dentsph::bonds
