// make_state: the initial State of a scene.
#include <algorithm>

#include "dentsph/scene.hpp"

namespace dentsph {

State make_state(const Scene& scene) {
  State state;
  // Both poses at the first keyframe, so that add_particles places the tool there and the first
  // step does not see the tool jump.
  state.tool_pose = scene.tool.at(0);
  state.tool_pose_applied = state.tool_pose;
  state.add_particles(scene.model, scene.particles);
  return state;
}

void intern_scene_materials(Scene& scene) {
  auto intern = [&](const std::vector<ParticleInit>& ps) {
    for (const ParticleInit& p : ps)
      if (p.material_index == kNoMaterial) scene.model.materials.intern(p.material);
  };
  intern(scene.particles);
  for (const ProcedureEvent& e : scene.events) intern(e.particles);
  // What an increment or a switch of instrument brings to a scene without paste or a tool.
  auto has = [&](Role r) {
    auto of = [&](const std::vector<ParticleInit>& ps) {
      return std::any_of(ps.begin(), ps.end(), [&](const ParticleInit& p) { return p.role == r; });
    };
    return of(scene.particles) ||
           std::any_of(scene.events.begin(), scene.events.end(), [&](const ProcedureEvent& e) { return of(e.particles); });
  };
  MaterialTable& table = scene.model.materials;
  if (!table.paste && !has(Role::material)) table.paste = table.intern(kDefaultPaste);
  if (!table.instrument && !has(Role::tool)) table.instrument = table.intern(kDefaultInstrument);
}

}  // namespace dentsph
