// Procedure events applied between steps (include/dentsph/scene.hpp).
#include <stdexcept>
#include <vector>

#include "dentsph/scene.hpp"
#include "dentsph/tools.hpp"

namespace dentsph {

namespace {

// The first event.count candidate sites that keep event.clearance from the material there.
std::vector<ParticleInit> free_sites(const State& state, const ProcedureEvent& event) {
  std::vector<Vec3> material;
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.role[i] == Role::material) material.push_back(state.pos[i]);
  const real c2 = event.clearance * event.clearance;
  std::vector<ParticleInit> ps;
  for (const ParticleInit& site : event.particles) {
    if (ps.size() == event.count) break;
    bool free = true;
    for (const Vec3& m : material)
      if (norm2(site.pos - m) < c2) {
        free = false;
        break;
      }
    if (free) ps.push_back(site);
  }
  return ps;
}

}  // namespace

void apply_event(const Scene& scene, State& state, const ProcedureEvent& event) {
  switch (event.kind) {
    case ProcedureEvent::Kind::dispense:
      state.add_particles(scene.model, event.count > 0 ? free_sites(state, event) : event.particles);
      return;
    case ProcedureEvent::Kind::switch_tool:
      replace_tool_particles(state, scene.model, event.particles);
      return;
  }
  throw std::logic_error("apply_event: unknown event kind");
}

}  // namespace dentsph
