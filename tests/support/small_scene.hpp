// A small scene built in code for tests of runners and sessions: a 4 x 4 x 3 block of paste on a
// plate (spacing 1 cm), a one-particle tool following `keyframes`.
#pragma once

#include <vector>

#include "dentsph/scene.hpp"
#include "support/builders.hpp"

namespace dentsph::testing {

inline Scene small_paste_scene(real dt, std::vector<ToolKeyframe> keyframes) {
  constexpr real s = 0.01;
  Scene sc;
  sc.name = "small";
  sc.source = "small.json";
  sc.params = params_for_spacing(s, {-0.05, -0.05, -0.05}, {0.1, 0.1, 0.1}, dt, {0, 0, -9.81});
  sc.model = make_model(sc.params);
  const real m = lattice_particle_mass(1000, s, sc.model.kernel);
  const Material paste{0.5, 60, 1000, 100}, wall{0.5, 200, 1000, 0};
  for (Vec3 p : lattice({0, 0, 0}, s, 4, 4, 3)) sc.particles.push_back(particle(Role::material, p, m, paste));
  for (Vec3 p : lattice({-2 * s, -2 * s, -2 * s}, s, 8, 8, 2)) sc.particles.push_back(particle(Role::boundary, p, m, wall));
  sc.particles.push_back(particle(Role::tool, {0, 0, 0}, m, wall));
  sc.tool.keyframes = std::move(keyframes);
  sc.output.snapshot_interval = 0.01;
  sc.material_spacing = s;
  intern_scene_materials(sc);
  sc.model.materials.paste = sc.model.materials.find(paste);
  return sc;
}

}  // namespace dentsph::testing
