// Procedure events applied between steps (include/dentsph/scene.hpp).
#include <stdexcept>

#include "dentsph/scene.hpp"
#include "dentsph/tools.hpp"

namespace dentsph {

void apply_event(const Scene& scene, State& state, const ProcedureEvent& event) {
  switch (event.kind) {
    case ProcedureEvent::Kind::dispense:
      state.add_particles(scene.model, event.particles);
      return;
    case ProcedureEvent::Kind::switch_tool:
      replace_tool_particles(state, scene.model, event.particles);
      return;
  }
  throw std::logic_error("apply_event: unknown event kind");
}

}  // namespace dentsph
