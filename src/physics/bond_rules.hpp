// The adhesion bonds' rules (docs/model.md, "Adhesion hysteresis"), written once for the CPU step
// (bonds/hysteresis.hpp, step/forces.cpp) and the CUDA stage bodies (backend/cuda/bond_slots.hpp,
// forces.hpp): a pair bonds when closer than A and may bond at all, and lets go when stretched past
// B; each event is counted once per pair. The stores that hold the bonds differ (BondStore on the
// CPU, fixed slots on the GPU); the decisions are these.
#pragma once

#include <cstdint>

#include "dentsph/config.hpp"
#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "physics/pair_terms.hpp"

namespace dentsph::bond_rules {

// The squared distances of the rules, taken once per particle (m^2).
struct Thresholds {
  real form_r2 = 0;   // A^2: closer than this, a pair that may bond bonds
  real break_r2 = 0;  // B^2: farther than this, a bond breaks
};
DENTSPH_HD inline Thresholds thresholds(const AdhesionParams& a) { return {a.A * a.A, a.B * a.B}; }

// A bonded pair at squared distance r2 lets go.
DENTSPH_HD inline bool stretched(real r2, const Thresholds& t) { return r2 > t.break_r2; }
// A pair at squared distance r2 is close enough to bond.
DENTSPH_HD inline bool close_enough(real r2, const Thresholds& t) { return r2 < t.form_r2; }

// Whether moving particle i may bond to j (not bonded yet): another particle, close enough, and a
// pair that may bond at all (pair::can_bond of their roles and adhesion strengths).
DENTSPH_HD inline bool may_form(std::uint32_t i, std::uint32_t j, real r2, const Thresholds& t, Role role_i,
                                Role role_j, real Ka_i, real Ka_j) {
  return j != i && close_enough(r2, t) && pair::can_bond(role_i, role_j, Ka_i, Ka_j);
}

// Whether moving particle i (stable id id_i) counts an event (a bond formed or broken) of its pair
// with j: each pair once, by the smaller id where both sides keep lists, by the moving side where
// j is a boundary particle (which keeps none).
DENTSPH_HD inline bool counts_event(std::uint32_t id_i, std::uint32_t id_j, Role role_j) {
  return id_i < id_j || role_j == Role::boundary;
}

}  // namespace dentsph::bond_rules
