// Force and torque of the particles on the tool (docs/model.md, "Haptic force"): the sum over tool
// particles of m_i a_i without gravity, a_i = f_i / rho_i, and its moment about the tool origin
// (each particle's term: physics/wrench.hpp).
#include "physics/wrench.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void compute_tool_wrench(State& s) {
  ToolWrench w;
  const Vec3 c = s.tool_pose_applied.position;
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    if (s.role[i] != Role::tool) continue;
    const physics::WrenchTerm t = physics::tool_wrench_term(s.force[i], s.mass[i], s.rho[i], s.pos[i], c);
    w.force += t.force;
    w.torque += t.torque;
  }
  s.tool_wrench = w;
}

}  // namespace dentsph::stages
