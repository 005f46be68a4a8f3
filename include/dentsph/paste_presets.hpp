// The filling pastes a dental scene can be filled with (docs/model.md, "Presets"): each a
// generalised Newtonian paste in SI units (material.hpp), its cure preset and the published figure
// its viscosity is anchored to. `run --material NAME` fills the built-in procedure with one and
// renders its force at scale 1.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dentsph/dental.hpp"
#include "dentsph/material.hpp"

namespace dentsph {

struct Scene;

struct PastePreset {
  std::string name;
  real temperature_c = 23;     // C, the paste's temperature (the consistency below is at it)
  Material paste;              // SI: consistency K (Pa s^n), flow index, yield stress, density, stiffness, adhesion
  std::string cure;            // its cure preset (cure_material.hpp): "composite" or "amalgam"
  real viscosity_at_10 = 0;    // Pa s, its viscosity at a shear rate of 10 /s (its yield stress's share included)
  real published_low = 0, published_high = 0;  // Pa s, the published range that figure sits in
  std::string source;          // the publication of that range, and which constants are assumed
  // Where one is published and no constant was set from it: the range of its viscosity over a
  // conventional composite's (the `universal` preset's), and its source (the rheometer's check).
  std::optional<std::array<real, 2>> published_ratio;
  std::string ratio_source;
};

// "flowable", "universal", "packable", "amalgam".
const std::vector<std::string>& paste_preset_names();

// The tension (Pa) a preset's contact with a steel instrument carries (Material::interface_strength):
// fitted to the probe-tack test's published peak pull on the universal preset, the same for every
// preset (docs/model.md, "Presets").
inline constexpr real kPasteSteelStrength = 5e4;
// A non-stick coated instrument's contact carries this at most (assumed: docs/model.md, "Presets").
inline constexpr real kCoatedStrength = 1e4;
// The instruments' surfaces: "steel", "coated".
const std::vector<std::string>& instrument_surface_names();
// The interface strength of an instrument of that surface (Material::interface_strength: 0 for
// steel, whose contact takes the paste's own). std::invalid_argument naming the choices.
real instrument_interface_strength(const std::string& surface);
// The preset of that name at `temperature_c` (10 to 70 C; 23 room, 37 mouth, 54 a pre-warmed
// composite): its consistency times paste_temperature_factor. std::invalid_argument naming the
// choices for another name, and the range for another temperature.
PastePreset paste_preset(const std::string& name, real temperature_c = 23);

// A composite's viscosity at `temperature_c` over its viscosity at 23 C: the Arrhenius factor
// exp(E/R (1/T - 1/T23)) with E/R = kPasteActivation (docs/model.md, "Presets").
inline constexpr real kPasteActivation = 3462;  // K
real paste_temperature_factor(real temperature_c);

// The viscous pressure's step (IisphParams::viscous_pressure) the presets are solved with, in the
// dental scenes and the handling tests: without it a stiff paste stays compressed by 2 to 10%
// (docs/model.md, "The viscous pressure").
inline constexpr real kPresetViscousPressure = 0.5;

// The paste preset a procedure file names in its "material" (docs/procedure-format.md), if any; none
// for an empty path (the built-in procedure names none). What fills a procedure is the caller's
// choice: `run --material` or a dental scene's "material" over the procedure's. Throws SceneError
// naming the file and the field.
std::optional<PastePreset> procedure_paste_preset(const std::filesystem::path& file);

// The dental scene's parameters for a preset: its paste, walls and instruments as stiff as it (the
// solve's walls give way otherwise), and the viscosity solved to a tolerance (a fixed count of
// iterations leaves a stiff paste's viscosity far from solved). The iisph solver alone: the preset
// is non-Newtonian, with the viscous pressure (kPresetViscousPressure). The paste's contact with the
// instruments keeps its strength (Material::interface_strength, the tack test's; docs/model.md, "Tack"):
// paste pulled past an instrument slips off it.
DentalSceneParams dental_params_for(const PastePreset& preset, DentalSceneParams base = {});
// Names `preset` as what fills `scene` (Scene::paste_preset and its temperature) and renders its
// force in newtons (Scene::force_scale 1).
void fill_scene_with(Scene& scene, const PastePreset& preset);
// The cure preset `scene`'s paste cures by (cure_material.hpp): its paste preset's ("amalgam" sets by
// itself, light or none), "composite" (by light) for a scene without one.
std::string scene_paste_cure(const Scene& scene);

}  // namespace dentsph
