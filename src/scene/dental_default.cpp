// Dental scenes: a tooth with its Class I cavity lined by boundary particles (src/tooth), filled
// with paste, and a ball tool that presses in and lifts. The built-in one uses the procedural
// molar crown; a scanned tooth can be given as a mesh file. The paper's
// counts: about 1600 material, 1400 boundary and 42 tool particles.
#include <algorithm>
#include <cmath>

#include "dentsph/dental.hpp"
#include "dentsph/solver.hpp"
#include "dentsph/tools.hpp"
#include "scene/paste_sites.hpp"

namespace dentsph {

real dental_time_step(Solver solver) { return solver_properties(solver).default_time_step(); }

IisphParams dental_iisph_params() {
  IisphParams p;
  p.omega = 0.7;
  return p;
}

Scene default_dental_scene(const DentalSceneParams& dp) {
  return dental_scene(default_tooth_scene(), dp, "dental_default", "built-in");
}

Scene dental_scene_from_mesh(const std::filesystem::path& mesh_file, const DentalSceneParams& dp) {
  return dental_scene(tooth_scene_from_mesh(mesh_file), dp, mesh_file.stem().string(), mesh_file.string());
}

Scene dental_base_scene(const ToothScene& ts, const DentalSceneParams& dp, const std::string& name,
                        const std::string& source) {
  const PreparedTooth& tooth = ts.tooth;
  const ToothFrame& fr = tooth.frame();
  const real s = ts.boundary.spacing;
  Scene sc;
  sc.name = name;
  sc.source = source;
  ModelParams& p = sc.params;
  p.dt = dp.dt > 0 ? dp.dt : dental_time_step(dp.solver);
  p.solver = dp.solver;
  set_lattice_spacing(p, s);
  p.gravity = fr.z * -9.81;
  p.neighbour_skin = 0.1 * p.h;  // its gain measured: docs/performance.md, "The step on the CPU"
  p.iisph = dp.iisph;
  p.hold_outside_domain = true;  // paste beyond the domain has fallen off the lined tooth
  const Bounds cb = tooth.cavity_bounds();
  const Vec3 pad{4e-3, 4e-3, 4e-3};
  p.domain_min = cb.min - pad;
  p.domain_max = cb.max + pad;
  sc.model = make_model(p);
  // The materials by name: the paste first, then the instruments, then the tooth, so that a particle
  // given by its values alone (an instrument's, which has the tooth's values) finds its own.
  MaterialTable& table = sc.model.materials;
  table.paste = table.add(kPasteMaterial, dp.paste);
  table.instrument = table.add(kInstrumentMaterial, dp.wall);
  const MaterialIndex tooth_material = table.add(kToothMaterial, dp.wall);
  const real m = lattice_particle_mass(dp.paste.rho0, s, sc.model.kernel);

  for (const Vec3& b : ts.boundary.points)
    sc.particles.push_back(make_particle(Role::boundary, b, m, dp.wall, {}, tooth_material));
  sc.tooth = tooth;
  sc.material_spacing = s;
  sc.output.snapshot_interval = 0.02;
  sc.force_scale = dental_force_scale;
  sc.dt_follows_solver = !(dp.dt > 0);
  attach_walls(sc);
  return sc;
}

Scene dental_scene(const ToothScene& ts, const DentalSceneParams& dp, const std::string& name,
                   const std::string& source) {
  Scene sc = dental_base_scene(ts, dp, name, source);
  const PreparedTooth& tooth = ts.tooth;
  const ToothFrame& fr = tooth.frame();
  const real s = ts.boundary.spacing;
  const real m = lattice_particle_mass(dp.paste.rho0, s, sc.model.kernel);

  // Paste on a lattice of the tooth frame: first the cavity (half a spacing clear of its walls),
  // then layers above the occlusal reference within the cavity's outline, up to the count.
  std::vector<Vec3> inside, above;
  for (const scene::PasteSite& p : scene::paste_sites(tooth, s))
    (p.in_cavity ? inside : above).push_back(fr.to_world(p.local));
  std::sort(above.begin(), above.end(),
            [&](const Vec3& a, const Vec3& b) { return dot(a - fr.origin, fr.z) < dot(b - fr.origin, fr.z); });
  const MaterialIndex paste = *sc.model.materials.paste;
  for (const Vec3& w : inside) sc.particles.push_back(make_particle(Role::material, w, m, dp.paste, {}, paste));
  for (std::size_t q = 0; q < above.size() && inside.size() + q < std::size_t(dp.material_particles); ++q)
    sc.particles.push_back(make_particle(Role::material, above[q], m, dp.paste, {}, paste));

  // The tool: a ball burnisher of 42 particles (52 as the iisph solver runs it), pressing 2.5
  // spacings into the paste and lifting, every 0.1 s.
  const ToolShape ball = tool_by_name("ball_burnisher", s, sc.model.solver);
  sc.instrument = ball.name;
  sc.instrument_spacing = s;
  for (const Vec3& b : ball.points)
    sc.particles.push_back(make_particle(Role::tool, b, m, dp.wall, {}, *sc.model.materials.instrument));
  real top = 0;
  for (const ParticleInit& q : sc.particles)
    if (q.role == Role::material) top = std::max(top, dot(q.pos - fr.origin, fr.z));
  const Vec3 above_paste = fr.origin + fr.z * (top + s);  // the ball's tip is the tool origin
  for (int c = 0; c <= 40; ++c)
    sc.tool.keyframes.push_back({0.05 * c, Pose{above_paste - fr.z * ((c % 2 ? 2.5 : 0.0) * s), {}}});
  sc.duration = 2.0;
  fit_dental_time_step(sc);
  return sc;
}

}  // namespace dentsph
