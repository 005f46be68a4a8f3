// Choosing the step that runs a scene after it was built (the command line's --solver), and the
// tool speed the iisph solver's velocity CFL limit is checked against.
#include "dentsph/dental.hpp"
#include "dentsph/scene.hpp"

namespace dentsph {

void select_solver(Scene& scene, Solver solver) {
  scene.params.solver = solver;
  if (scene.dt_follows_solver) scene.params.dt = dental_time_step(solver);
  MaterialTable materials = std::move(scene.model.materials);  // the scene's, not the parameters'
  scene.model = make_model(scene.params);
  scene.model.materials = std::move(materials);
}

real scene_tool_speed(const Scene& scene) {
  std::vector<Vec3> anchors;
  for (const ParticleInit& p : scene.particles)
    if (p.role == Role::tool) anchors.push_back(p.pos);
  for (const ProcedureEvent& e : scene.events)
    if (e.kind == ProcedureEvent::Kind::switch_tool)
      for (const ParticleInit& p : e.particles) anchors.push_back(p.pos);
  return scene.tool.max_speed(anchors);
}

}  // namespace dentsph
