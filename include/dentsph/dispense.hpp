// What a user asks for between steps: increments of filling material dropped into the cavity
// (the dental procedure's "dispense": the viewer's D key and the haptic device's button 1 both
// place one here) and a switch of instrument (the viewer's tool menu), each as a recorded
// session's replay repeats it.
#pragma once

#include <cstddef>
#include <string>

#include "dentsph/scene.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

// The first particle of `role` in the scene (its particles, then its events'), or null.
const ParticleInit* first_particle(const Scene& scene, Role role);

// The paste an increment is made of: the Model's named paste (MaterialTable::paste) with the mass
// of the scene's first paste particle (or the lattice mass of the increment spacing); without a
// named paste, the scene's first material particle's, or a default paste.
struct IncrementPaste {
  real mass = 0;  // kg per particle
  Material material;
  MaterialIndex material_index = kNoMaterial;  // its entry of Model::materials (kNoMaterial: by value)
};
IncrementPaste scene_paste(const Scene& scene);

// The material of the scene's instruments: the Model's named instrument material, else its first
// tool particle's, or a default wall; and its entry of the table (kNoMaterial: by value).
Material scene_tool_material(const Scene& scene);
MaterialIndex scene_tool_material_index(const Scene& scene);

// Replaces the tool by the instrument `name` (tool_by_name at the increment spacing, with the
// paste's particle mass and the scene's tool material), at the tool's applied pose. Throws
// std::invalid_argument for an unknown name.
void switch_instrument(const Scene& scene, State& state, const std::string& name);

// The lattice spacing of an increment: the scene's material spacing, or half the kernel radius.
real increment_spacing(const Scene& scene);
// The default increment's volume (m^3): a sixth of the cavity, or 200 particles without a tooth.
real default_increment_volume(const Scene& scene);
// The increment volume a session asks for (m^3), or the default one when it asks for 0 (or less):
// the one reading of "0 means the scene's default" for the runtime, its recording, replay and the
// viewer.
real increment_volume_or_default(const Scene& scene, real requested);
// The direction increments drop along: the tooth's axis (its frame's z), or +z without a tooth.
Vec3 increment_axis(const Scene& scene);

// The paste in `state`: the sum of its particles' volumes at rest (m / rho0), moving or set by the
// cure, m^3.
real material_volume(const State& state);
// The most paste increments may bring a scene to (m^3): limits::max_material_per_cavity times the
// cavity's volume, or the grid domain's volume without a tooth.
real max_material_volume(const Scene& scene);

// Adds (between steps) a ball of `volume` m^3 of `paste` on the line along `up` through the
// tooth's origin (or the middle of the domain without a tooth), its lowest point two spacings
// above the highest material on that axis. Returns the number of particles added: 0 when the
// increment is refused, because the paste would then exceed max_material_volume (however often a
// button is pressed, the cavity holds only so much) or the state limits::max_particles.
std::size_t dispense_increment(const Scene& scene, State& state, real volume, const Vec3& up,
                               const IncrementPaste& paste);

}  // namespace dentsph
