// Procedure events applied between steps (include/dentsph/scene.hpp).
#include <stdexcept>

#include "dentsph/scene.hpp"

namespace dentsph {

void apply_event(const Scene& scene, State& state, const ProcedureEvent& event) {
  switch (event.kind) {
    case ProcedureEvent::Kind::dispense:
      state.add_particles(scene.model, event.particles);
      return;
    case ProcedureEvent::Kind::switch_tool: {
      std::vector<std::uint8_t> remove(state.size(), 0);
      for (std::uint32_t i = 0; i < state.size(); ++i) remove[i] = state.role[i] == Role::tool;
      state.remove_particles(scene.model, remove);
      state.add_particles(scene.model, event.particles);  // at tool_pose_applied
      return;
    }
  }
  throw std::logic_error("apply_event: unknown event kind");
}

}  // namespace dentsph
