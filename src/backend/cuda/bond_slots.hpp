// Adhesion bonds on the GPU: each particle's fixed-capacity list of partner ids (BondStore's
// layout), and the hysteresis of bonds/hysteresis.hpp on those slots. Each particle changes only
// its own list, from the squared distance its partner sees too, so the decision is symmetric and
// a thread per particle writes without conflicts; a full list refuses the partner and counts an
// overflow. Events are counted once per pair, as on the CPU.
#pragma once

#include "backend/cuda/view.hpp"
#include "physics/bond_rules.hpp"

namespace dentsph::gpu {

DENTSPH_HD inline bool bonded(const StepView& v, std::uint32_t id, std::uint32_t other) {
  const std::uint32_t* p = v.bond_partner + std::size_t(id) * v.bond_capacity;
  const std::uint32_t c = v.bond_count[id];
  for (std::uint32_t k = 0; k < c; ++k)
    if (p[k] == other) return true;
  return false;
}

// Removes the k-th partner of `id` (the last one takes its place).
DENTSPH_HD inline void remove_bond(const StepView& v, std::uint32_t id, std::uint32_t k) {
  std::uint32_t* p = v.bond_partner + std::size_t(id) * v.bond_capacity;
  p[k] = p[--v.bond_count[id]];
}

// Counts the break of the bond of moving particle i to j (sorted indices), once per pair.
DENTSPH_HD inline void count_break(const StepView& v, std::uint32_t i, std::uint32_t j, BondEvents& ev) {
  if (bond_rules::counts_event(v.p.id[i], v.p.id[j], v.p.role[j])) ++ev.broken;
}

// Bonds moving particle i to j (sorted indices, squared distance r2) if they are closer than A,
// may bond and are not bonded yet.
DENTSPH_HD inline void try_form(const StepView& v, std::uint32_t i, std::uint32_t j, real r2,
                                const bond_rules::Thresholds& t, BondEvents& ev) {
  if (!bond_rules::may_form(i, j, r2, t, v.p.role[i], v.p.role[j], v.p.Ka[i], v.p.Ka[j])) return;
  const std::uint32_t a = v.p.id[i], b = v.p.id[j];
  if (bonded(v, a, b)) return;
  if (v.bond_count[a] >= std::uint32_t(v.bond_capacity)) {
    ++ev.overflowed;
    return;
  }
  v.bond_partner[std::size_t(a) * v.bond_capacity + v.bond_count[a]++] = b;
  if (bond_rules::counts_event(a, b, v.p.role[j])) ++ev.formed;
}

}  // namespace dentsph::gpu
