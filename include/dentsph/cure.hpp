// Light curing and setting (docs/model.md, "Curing"): between steps, the curing light's beam is
// attenuated through the paste, the tooth and the instrument in front of each paste particle
// (Beer-Lambert); the radiant exposure each receives raises its degree of conversion (or, for a
// self-setting material, time does); the conversion stiffens the paste (cured_parameters), and
// past the gel point a particle becomes rigid: a static boundary particle that keeps its place,
// shrinking with its increment as its conversion rises.
//
// The run loops call cure_between_steps() once after every step (docs/architecture.md, "Curing").
#pragma once

#include <cstdint>
#include <optional>

#include "dentsph/cure_material.hpp"
#include "dentsph/curing_light.hpp"
#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

struct CureModel {
  CureMaterial paste;               // how every paste particle (added as Role::material) cures
  // m: the particles' lattice spacing. In the light transport each particle stands for spacing^3
  // of matter, and the beam's grid has cells of this size.
  real spacing = 0;
  real tissue_attenuation = 5000;   // 1/m, boundary particles other than set paste (the tooth)
  real tool_attenuation = 1e5;      // 1/m, the instrument's particles (metal: opaque)
  // Pa s: the largest viscosity cured_parameters may give (make_cure_model: half the viscous
  // stability limit of the Model's dt), so that stiffening never makes the step unstable.
  real viscosity_limit = 1e30;
  // s between cure passes (cure_between_steps): the light's transport, the conversion and the
  // paste's parameters, the gel transition and shrinkage (a pass that sets or moves paste makes the
  // next step rebuild its lists and the boundary's static density). Between passes a step adds only
  // the dose, from the last transport's irradiance.
  real transition_interval = 1e-3;
  // m: rigid paste is moved to its shrunk place once some particle's place has moved this far.
  real shrink_tolerance = 0;
};

// A CureModel for `paste` on particles of `spacing` stepped by `model` (its viscosity limit from
// model.dt and h, and the paste's uncured rest density and viscosity), shrink tolerance 1% of the
// spacing. Throws std::invalid_argument for a non-positive spacing or an inconsistent material.
CureModel make_cure_model(const Model& model, const CureMaterial& paste, real spacing, const Material& uncured);

// What one cure update changed.
struct CureUpdate {
  std::uint32_t lit = 0;          // paste particles the light reaches (at its last transport)
  std::uint32_t converted = 0;    // paste particles whose conversion rose (a pass)
  std::uint32_t set = 0;          // particles that became rigid (gel point passed)
  bool moved = false;             // rigid particles were moved by shrinkage
  // Particles' roles, positions or parameters changed: a GPU stepper must take them up again.
  bool changed() const { return converted > 0 || set > 0 || moved; }
};

// The one entry point, called between steps (after each step, with the step's dt and the light
// that is on, ActiveLights): every call adds the radiant exposure of dt to each lit paste particle;
// every transition_interval of State::time (and at once when the light comes on or goes off; a
// light that moves is taken at the next pass) a pass recomputes the light's transport, each particle's conversion (from its dose, or its age
// for a self-setting material) and its parameters (cured_parameters), turns paste past its gel
// point rigid and moves rigid paste as it shrinks. Without light and with nothing setting, a call
// returns at once. Any dt works: a loop may advance the cure in larger steps while the paste is at
// rest under the light (each call then is a pass).
CureUpdate cure_between_steps(const CureModel& cure, State& state, const std::optional<CuringLight>& light, real dt);

// Whether the next cure_between_steps(cure, state, light, dt) makes a pass (reads and may change
// the particles): a light turned on or off, or the pass's interval run out. Without a pass the call
// only adds the dose, from the cure state alone (a GPU backend need not download the particles).
bool cure_pass_due(const CureModel& cure, const State& state, const std::optional<CuringLight>& light);

// The light transport alone: state.cure.irradiance of every paste particle (W/m^2; 0 outside the
// beam or behind the window) and the list of the lit ones (cure.lit_ids). Returns how many are lit.
// Part of cure_between_steps' pass.
std::uint32_t compute_irradiance(const CureModel& cure, State& state, const CuringLight& light);

// The gel transition and shrinkage alone (part of cure_between_steps' pass):
// paste past alpha_gel becomes rigid, and rigid paste moves towards its increment's centroid as it
// shrinks. Returns what it did (set, moved).
CureUpdate apply_cure_transition(const CureModel& cure, State& state);

}  // namespace dentsph
