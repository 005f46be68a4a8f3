// What the handling tests' rigs share: a model of the paste's spacing for the iisph solver with its
// solves run to a tolerance, and stepping it with the run's threads and progress.
#pragma once

#include <string>
#include <vector>

#include "dentsph/handling.hpp"
#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph::handling {

// The model of a rig of spacing s (set_lattice_spacing, as the dental scenes) over [lo, hi], on the
// iisph solver: cg pressure, the viscosity solved to 1e-4.
ModelParams rig_params(real s, const Vec3& lo, const Vec3& hi, real dt, const Vec3& gravity);

// The plates', moulds' and probes' material beside `paste`: as stiff as the dental walls (1.5 Kp),
// of its density, no adhesion of its own.
Material wall_beside(const Material& paste);

// An empty result of the test named `test` on `preset` (its material and temperature).
HandlingResult result_of(const std::string& test, const PastePreset& preset);

// One step; std::runtime_error naming the test when a particle's state is not finite or the tool
// force has exploded (step.hpp).
void rig_step(const Model& model, State& state, const HandlingRunOptions& run, const std::string& test);

}  // namespace dentsph::handling

namespace dentsph::handling {

// Paste filling a cylindrical mould level with its rim (floor and wall boundary particles two
// layers deep), and a flat probe above it: the tool, a solid cylinder of particles 3 mm tall (a
// shell two layers deep let a stiff paste through its face: docs/model.md, "Presets"), its first
// layer two spacings (the kernel's support) above the paste's top layer, so that it starts out of
// reach. The packing and tack tests' rig; gravity acts.
struct MouldRig {
  Model model;
  State state;
  real face_gap = 0;  // m from the probe's face (half a spacing under its first layer) to the paste's surface
};
// `probe_strength`: the probe's Material::interface_strength (0: steel's, none of its own).
MouldRig mould_rig(const PastePreset& preset, real spacing, real mould_diameter, real mould_depth,
                   real probe_diameter, real dt, real probe_strength = 0);

// The probe driven down at `speed` to `depth` below the paste's surface, then held still for
// `hold`: the stress under it (its force over its face's area) at every step.
struct ProbePress {
  std::vector<real> t, stress;  // s, MPa
  real peak = 0;                // MPa
  real peak_force = 0;          // N, the force under the probe at that peak
  real end = 0;                 // MPa, the mean over the hold's second half (0 without a hold)
};
ProbePress press_probe(MouldRig& rig, real probe_diameter, real speed, real depth, real hold, real dt,
                       const HandlingRunOptions& run, const std::string& test);

}  // namespace dentsph::handling
