// The cure state of each particle (docs/model.md, "Curing"): degree of conversion, the radiant
// exposure it has received, the increment it was placed with. Kept by stable id, like the bonds
// and the boundary's static density, so the reordering of every step (src/step/reorder.cpp) and
// a GPU stepper's own cell order leave it alone; State::add_particles and remove_particles keep
// it sized and keyed.
#pragma once

#include <cstdint>
#include <vector>

#include "dentsph/curing_light.hpp"
#include "dentsph/material.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {

struct ParticleInit;

class CureState {
 public:
  // ---- by stable id, [particles()] each ------------------------------------------------------
  std::vector<real> alpha;                // degree of conversion, 0 to the material's alpha_max
  std::vector<real> dose;                 // J/m^2, radiant exposure received (1 J/cm^2 = 1e4 J/m^2)
  std::vector<real> irradiance;           // W/m^2 reaching the particle at the last cure update
  std::vector<std::uint16_t> increment;   // 0: the scene's own paste (or not paste); k: the k-th
                                          // increment dispensed (begin_increment)
  std::vector<std::uint8_t> curable;      // paste: added as Role::material; stays so when it sets
  std::vector<std::uint8_t> rigid;        // set past the gel point: now a static boundary particle
  std::vector<real> mixed_at;             // s, State::time when the particle was added
  // The parameters the paste was added with (mu, Kp, rho0, Ka): what the cure mapping starts from.
  std::vector<real> mu0, Kp0, rho00, Ka0;
  // The parameters the conversion has given each particle (cured_parameters), where the State marks
  // its material kCuredMaterial: what State::refresh_materials and the reorder write for it in place
  // of the Model's table. Empty until the first conversion (set_cured).
  std::vector<Material> cured;
  std::vector<Vec3> gel_pos;              // m, where the particle was when it set (rigid only)

  std::uint16_t increments = 0;           // increments begun so far
  // The cure pass (transport, conversion, parameters, transition; cure_between_steps): when the
  // next is due (s, State::time), and the light the last one saw.
  real next_pass = 0;
  bool light_on = false;
  CuringLight light;

  // ---- the light transport's results and scratch (sized on demand, kept between calls) --------
  std::vector<std::uint32_t> lit_ids;        // ids of the paste particles the light reaches
  std::vector<real> lit_irradiance;          // W/m^2 on each, in the same order
  std::vector<real> beam_x, beam_y, beam_z;  // [n] by index: each particle in the beam's frame
  std::vector<real> beam_grid;               // attenuation per node, then its column integrals
  std::vector<Vec3> increment_sum;           // [increments + 1] shrinkage: mass-weighted gel places
  std::vector<real> increment_mass;          // [increments + 1] and masses of the set paste

  std::uint32_t particles() const { return std::uint32_t(alpha.size()); }

  // Appends the next id's entries for a particle added at `time`.
  void append(const ParticleInit& p, real time);
  // Records `m` as the parameters the cure has given particle `id` (sizes `cured` the first time).
  void set_cured(std::uint32_t id, const Material& m);
  // Re-keys after State::remove_particles: new_id[old] is the kept particle's new id (~0u: gone).
  void compact(const std::vector<std::uint32_t>& new_id, std::uint32_t kept);
  // The paste particles with ids in [first_id, first_id + count) are one new increment (a
  // dispense): they get its number. Returns it.
  std::uint16_t begin_increment(std::uint32_t first_id, std::uint32_t count);
  // Bytes held per particle (for State::bytes_per_particle).
  std::size_t bytes() const;
};

}  // namespace dentsph
