// Procedure events applied between steps (include/dentsph/scene.hpp).
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "dentsph/scene.hpp"
#include "dentsph/tools.hpp"
#include "tooth/disk_set.hpp"

namespace dentsph {

namespace {

// The first event.count candidate sites that keep event.clearance from the paste there, moving or
// set by the cure (the paste in a DiskSet of that radius: each site looks at the points near it,
// linear in the paste and the sites instead of their product).
std::vector<ParticleInit> free_sites(const State& state, const ProcedureEvent& event) {
  std::vector<ParticleInit> ps;
  DiskSet material(event.clearance);  // no clearance: nothing is near
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.is_paste(i) && is_finite(state.pos[i])) material.add(state.pos[i]);  // set paste too
  for (const ParticleInit& site : event.particles) {
    if (ps.size() == event.count) break;
    if (!material.near(site.pos)) ps.push_back(site);
  }
  return ps;
}

}  // namespace

void apply_event(const Scene& scene, State& state, const ProcedureEvent& event) {
  switch (event.kind) {
    case ProcedureEvent::Kind::dispense: {
      const std::uint32_t first = state.size();
      state.add_particles(scene.model, event.count > 0 ? free_sites(state, event) : event.particles);
      state.cure.begin_increment(first, state.size() - first);
      return;
    }
    case ProcedureEvent::Kind::switch_tool:
      replace_tool_particles(state, scene.model, event.particles);
      return;
    case ProcedureEvent::Kind::cure:
      return;  // the light is looked up each step (ActiveLights)
  }
  throw std::logic_error("apply_event: unknown event kind");
}

}  // namespace dentsph
