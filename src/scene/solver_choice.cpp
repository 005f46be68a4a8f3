// Choosing the step that runs a scene after it was built (the command line's --solver), the walls
// the iisph solver keeps material out of, and the tool speed the iisph solver's velocity CFL limit
// is checked against.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "dentsph/dental.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/solver.hpp"
#include "dentsph/tools.hpp"

namespace dentsph {

namespace {
constexpr real inf = std::numeric_limits<real>::infinity();
constexpr real kMaxWallNodes = 2e6;
}  // namespace

void select_solver(Scene& scene, Solver solver) {
  if (solver != Solver::iisph)
    if (const std::optional<MaterialIndex> m = scene.model.materials.first_non_newtonian())
      throw std::invalid_argument(fmt::format(
          "the material \"{}\" is non-Newtonian (flow_index {}, yield_stress {} Pa) and only the iisph solver steps a "
          "rheology: run it with --solver iisph on the CPU backend (the GPU backends have the paper's step alone)",
          scene.model.materials.name(*m), scene.model.materials[*m].flow_index, scene.model.materials[*m].yield_stress));
  // The particles' masses are the lattice mass of the scene's density kernel (lattice_particle_mass):
  // a switch that changes the kernel would start the paste 1% off its rest density.
  if (scene.params.iisph.density_kernel == DensityKernel::cubic && solver != scene.params.solver)
    throw std::invalid_argument(fmt::format(
        "the scene sums its density with the cubic spline (iisph.density_kernel \"cubic\"), which only the iisph "
        "solver does, and its particles' masses are that kernel's: run it on the {} solver it names (without --solver "
        "{}, on the CPU backend), or set iisph.density_kernel to \"poly6\"",
        solver_name(scene.params.solver), solver_name(solver)));
  scene.params.solver = solver;
  MaterialTable materials = std::move(scene.model.materials);  // the scene's, not the parameters'
  scene.model = make_model(scene.params);
  scene.model.materials = std::move(materials);
  attach_walls(scene);
  shape_instruments(scene);
  fit_dental_time_step(scene);
}

std::string choose_solver(Scene& scene, const std::string& named, bool gpu_backend) {
  if (!named.empty()) {
    const std::optional<Solver> s = solver_from_name(named);
    if (!s) throw std::invalid_argument(fmt::format("--solver {}: unknown solver; choose {}", named, solver_choices()));
    if (*s != scene.model.solver) select_solver(scene, *s);  // the scene's own already made for it
    return {};
  }
  if (!gpu_backend || scene.model.solver == Solver::paper) return {};
  const Solver was = scene.model.solver;
  select_solver(scene, Solver::paper);
  return fmt::format("the GPU backend runs the paper's step (the scene's {} solver has none there): --solver paper, "
                     "dt = {:.3g} s",
                     solver_name(was), double(scene.model.dt));
}

void fit_dental_time_step(Scene& scene) {
  if (!scene.dt_follows_solver) return;
  const StepSolver& solver = solver_properties(scene.model.solver);
  real dt = solver.default_time_step();
  const real limit = solver.tool_speed_limit(scene.model, scene_tool_speed(scene));
  if (dt > limit) {
    constexpr real tick = 1e-5;
    dt = std::floor(limit / tick) * tick;
    if (dt > limit) dt -= tick;
    dt = std::max(dt, tick);  // a tool this fast is refused by the run's check, naming it
  }
  scene.params.dt = dt;
  scene.model.dt = dt;
}

namespace {

// `particles` (one instrument's, tool frame) made again as `name` at `spacing` for `solver`, with
// the first one's mass and material.
void remake(std::vector<ParticleInit>& particles, const std::string& name, real spacing, Solver solver) {
  if (particles.empty()) return;
  const ParticleInit like = particles.front();
  particles.clear();
  for (const Vec3& p : tool_by_name(name, spacing, solver).points)
    particles.push_back(make_particle(Role::tool, p, like.mass, like.material, {}, like.material_index));
}

}  // namespace

void shape_instruments(Scene& scene) {
  const Solver solver = scene.model.solver;
  if (!scene.instrument.empty() && scene.instrument_spacing > 0) {
    // In the place of the old ones (the particles' order is the run's).
    const auto is_tool = [](const ParticleInit& p) { return p.role == Role::tool; };
    const auto first = std::find_if(scene.particles.begin(), scene.particles.end(), is_tool);
    const std::ptrdiff_t at = first - scene.particles.begin();
    std::vector<ParticleInit> tool;
    std::copy_if(first, scene.particles.end(), std::back_inserter(tool), is_tool);
    std::erase_if(scene.particles, is_tool);
    remake(tool, scene.instrument, scene.instrument_spacing, solver);
    scene.particles.insert(scene.particles.begin() + at, tool.begin(), tool.end());
  }
  for (ProcedureEvent& e : scene.events)
    if (e.kind == ProcedureEvent::Kind::switch_tool && !e.tool.empty() && e.tool_spacing > 0)
      remake(e.particles, e.tool, e.tool_spacing, solver);
}

void attach_walls(Scene& scene) {
  if (!solver_properties(scene.model.solver).uses_walls()) {
    scene.model.walls.reset();
    return;
  }
  if (!scene.model.walls) scene.model.walls = tooth_wall_field(scene);
}

std::shared_ptr<const WallField> tooth_wall_field(const Scene& scene, bool whole_tooth) {
  if (!scene.tooth || !(scene.material_spacing > 0)) return nullptr;
  Vec3 lo{inf, inf, inf}, hi = -lo;
  for (const ParticleInit& p : scene.particles)
    if (p.role == Role::boundary) {
      lo = vmin(lo, p.pos);
      hi = vmax(hi, p.pos);
    }
  if (!(lo.x <= hi.x)) return nullptr;  // no walls
  const real h = scene.model.kernel.h, s = scene.material_spacing;
  const Vec3 pad{h, h, h};
  // Over the lining's box grown by h and the whole domain, where paste may be: overfill spreads
  // over the tooth beyond its lining, where no boundary particle holds it out.
  lo = lo - pad;
  hi = hi + pad;
  if (scene.model.domain_min.x < scene.model.domain_max.x) {
    lo = vmin(lo, scene.model.domain_min);
    hi = vmax(hi, scene.model.domain_max);
  }
  if (whole_tooth) {  // the whole crown and a margin the instrument's ball reaches
    const Bounds b = scene.tooth->tooth().bounds();
    lo = vmin(lo, b.min - pad * 2);
    hi = vmax(hi, b.max + pad * 2);
  }
  const Vec3 span = hi - lo;
  // Cells of half a spacing, larger where the box would need more than kMaxWallNodes corners (a
  // scene far larger than a tooth's: the field's cost stays that of a large tooth's).
  const real cell = std::max<real>(0.5 * s, std::cbrt(span.x * span.y * span.z / kMaxWallNodes));
  const PreparedTooth tooth = *scene.tooth;
  return std::make_shared<const WallField>([&tooth](const Vec3& p) { return tooth.distance(p).distance; }, lo, hi,
                                           cell, 0.25 * s);
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
