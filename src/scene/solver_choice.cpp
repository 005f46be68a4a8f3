// Choosing the step that runs a scene after it was built (the command line's --solver), the walls
// the iisph solver keeps material out of, and the tool speed the iisph solver's velocity CFL limit
// is checked against.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "dentsph/dental.hpp"
#include "dentsph/scene.hpp"

namespace dentsph {

namespace {
constexpr real inf = std::numeric_limits<real>::infinity();
constexpr real kMaxWallNodes = 1e6;
}  // namespace

void select_solver(Scene& scene, Solver solver) {
  scene.params.solver = solver;
  if (scene.dt_follows_solver) scene.params.dt = dental_time_step(solver);
  MaterialTable materials = std::move(scene.model.materials);  // the scene's, not the parameters'
  scene.model = make_model(scene.params);
  scene.model.materials = std::move(materials);
  attach_walls(scene);
}

void attach_walls(Scene& scene) {
  if (scene.model.solver != Solver::iisph || !scene.tooth || !(scene.material_spacing > 0)) {
    scene.model.walls.reset();
    return;
  }
  if (scene.model.walls) return;
  Vec3 lo{inf, inf, inf}, hi = -lo;
  for (const ParticleInit& p : scene.particles)
    if (p.role == Role::boundary) {
      lo = {std::min(lo.x, p.pos.x), std::min(lo.y, p.pos.y), std::min(lo.z, p.pos.z)};
      hi = {std::max(hi.x, p.pos.x), std::max(hi.y, p.pos.y), std::max(hi.z, p.pos.z)};
    }
  if (!(lo.x <= hi.x)) return;  // no walls
  const real h = scene.model.kernel.h, s = scene.material_spacing;
  const Vec3 pad{h, h, h}, span = hi - lo + pad * 2;
  // Cells of half a spacing, larger where the box would need more than kMaxWallNodes corners (a
  // scene far larger than a tooth's: the field's cost stays that of a large tooth's).
  const real cell = std::max<real>(0.5 * s, std::cbrt(span.x * span.y * span.z / kMaxWallNodes));
  const PreparedTooth tooth = *scene.tooth;
  scene.model.walls = std::make_shared<const WallField>([&tooth](const Vec3& p) { return tooth.distance(p).distance; },
                                                        lo - pad, hi + pad, cell, 0.25 * s);
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
