// The tool wrench on the GPU (physics/wrench.hpp, as the CPU's tool_wrench.cpp): each tool
// particle's m_i a_i = f_i V_i and its moment about the tool origin; the sums are taken per block of kBlock particles and the
// blocks' partial sums added in a fixed order (reduce.hpp), so the result is deterministic.
#pragma once

#include "backend/cuda/view.hpp"
#include "physics/wrench.hpp"

namespace dentsph::gpu {

DENTSPH_HD inline StepSums wrench_term(const StepView& v, std::uint32_t i) {
  StepSums s;
  if (v.p.role[i] != Role::tool) return s;
  const physics::WrenchTerm t =
      physics::tool_wrench_term(v.force[i], v.p.mass[i], v.rho[i], v.p.pos[i], v.tool->applied);
  s.force = t.force;
  s.torque = t.torque;
  return s;
}

}  // namespace dentsph::gpu
