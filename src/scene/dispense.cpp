// Increments of material on request (dispense.hpp).
#include "dentsph/dispense.hpp"

#include <algorithm>
#include <cmath>

#include "dentsph/limits.hpp"
#include "dentsph/tools.hpp"
#include "dentsph/tooth.hpp"
#include "physics/kernels.hpp"

namespace dentsph {

const ParticleInit* first_particle(const Scene& scene, Role role) {
  for (const ParticleInit& p : scene.particles)
    if (p.role == role) return &p;
  for (const ProcedureEvent& e : scene.events)
    for (const ParticleInit& p : e.particles)
      if (p.role == role) return &p;
  return nullptr;
}

real increment_spacing(const Scene& scene) {
  return scene.material_spacing > 0 ? scene.material_spacing : 0.5 * scene.model.kernel.h;
}

IncrementPaste scene_paste(const Scene& scene) {
  const MaterialTable& table = scene.model.materials;
  if (table.paste) {
    const Material& m = table[*table.paste];
    for (const ParticleInit& p : scene.particles)
      if (p.material_index == *table.paste || (p.material_index == kNoMaterial && p.role == Role::material && p.material == m))
        return {p.mass, m, *table.paste};
    return {lattice_particle_mass(m.rho0, increment_spacing(scene), scene.model.kernel), m, *table.paste};
  }
  if (const ParticleInit* p = first_particle(scene, Role::material)) return {p->mass, p->material, kNoMaterial};
  const Material m = kDefaultPaste;
  return {lattice_particle_mass(m.rho0, increment_spacing(scene), scene.model.kernel), m, kNoMaterial};
}

Material scene_tool_material(const Scene& scene) {
  const MaterialTable& table = scene.model.materials;
  if (table.instrument) return table[*table.instrument];
  const ParticleInit* tool = first_particle(scene, Role::tool);
  return tool ? tool->material : kDefaultInstrument;
}

MaterialIndex scene_tool_material_index(const Scene& scene) {
  return scene.model.materials.instrument.value_or(kNoMaterial);
}

void switch_instrument(const Scene& scene, State& state, const std::string& name) {
  switch_tool(state, scene.model, tool_by_name(name, increment_spacing(scene), scene.model.solver), scene_paste(scene).mass,
              scene_tool_material(scene), scene_tool_material_index(scene));
}

real default_increment_volume(const Scene& scene) {
  const real s = increment_spacing(scene);
  return scene.tooth ? scene.tooth->cavity_volume() / 6 : 200 * s * s * s;
}

real increment_volume_or_default(const Scene& scene, real requested) {
  return requested > 0 ? requested : default_increment_volume(scene);
}

Vec3 increment_axis(const Scene& scene) { return scene.tooth ? scene.tooth->frame().z : Vec3{0, 0, 1}; }

real material_volume(const State& state) {
  real v = 0;
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.is_paste(i)) v += state.mass[i] / state.rho0[i];  // set paste too
  return v;
}

real max_material_volume(const Scene& scene) {
  if (scene.tooth) return limits::max_material_per_cavity * scene.tooth->cavity_volume();
  const Vec3 d = scene.model.domain_max - scene.model.domain_min;
  return d.x * d.y * d.z;
}

std::size_t dispense_increment(const Scene& scene, State& state, real volume, const Vec3& up,
                               const IncrementPaste& paste) {
  const real s = increment_spacing(scene);
  if (!(volume > 0) || material_volume(state) + volume > max_material_volume(scene) ||
      double(state.size()) + increment_points_bound(volume, s) > double(limits::max_particles))
    return 0;
  const real r = std::cbrt(3 * volume / (4 * kernels::pi));
  const Vec3 axis_origin =
      scene.tooth ? scene.tooth->frame().origin : 0.5 * (scene.model.domain_min + scene.model.domain_max);
  real top = 0;
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.is_paste(i)) top = std::max(top, dot(state.pos[i] - axis_origin, up));  // set paste too
  const Vec3 centre = axis_origin + up * (top + r + 2 * s);
  const std::vector<ParticleInit> ps = material_increment(centre, volume, s, paste.mass, paste.material, paste.material_index);
  const std::uint32_t first = state.size();
  state.add_particles(scene.model, ps);
  state.cure.begin_increment(first, std::uint32_t(ps.size()));
  return ps.size();
}

}  // namespace dentsph
