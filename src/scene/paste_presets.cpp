// The filling pastes (include/dentsph/paste_presets.hpp; constants and sources in docs/model.md,
// "Presets").
#include "dentsph/paste_presets.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dentsph/scene.hpp"
#include "physics/rheology.hpp"

namespace dentsph {

namespace {

// A composite whose viscosity at 10 /s is eta10 (the yield stress's share, yield_stress / 10 s,
// included) with flow index n: the consistency K = (eta10 - yield_stress / 10 s) 10^(1 - n); its
// viscosity capped at `plateau` (a low-shear Newtonian plateau), or at 1e6 Pa s where that is 0
// (the cap of a paste that stands: docs/model.md, "Rheology").
Material composite(real eta10, real n, real yield_stress, real plateau, real rho0, real Kp) {
  Material m;
  m.mu = (eta10 - yield_stress / 10) * std::pow(10.0, 1 - n);
  m.flow_index = n;
  m.yield_stress = yield_stress;
  m.max_viscosity = plateau > 0 ? plateau : 1e6;
  m.rho0 = rho0;
  m.Kp = Kp;
  m.Ka = 50;
  m.interface_strength = kPasteSteelStrength;
  return m;
}

// The presets' constants (docs/model.md, "Presets"): viscosity at 10 /s (Pa s, 23 C, its yield
// stress's share included), flow index, yield stress (Pa), low-shear plateau (Pa s at 23 C; 0:
// none), density (kg/m^3), stiffness Kp (m^2/s^2), cure preset, the published range of the viscosity and its source, and a
// published range of its ratio to a conventional composite's not used to set it (0, 0: none).
struct PresetRow {
  const char* name;
  real eta10, n, yield_stress, plateau, rho0, Kp;
  const char* cure;
  real low, high;
  const char* source;
  real ratio_low = 0, ratio_high = 0;
  const char* ratio_source = "";
};

constexpr PresetRow kPresets[] = {
    {"flowable", 1700, 0.5, 0, 1700, 2000, 1e4, "composite", 1310, 2200,
     "Loumprinis et al., Dent Mater 2021: flowables 1.31 to 2.20 kPa s at 23 C", 0.04, 0.56,
     "Lee, Son & Um (Dent Mater 2003): flowables 0.04 to 0.56 of a conventional hybrid (Z-100) at 10 rad/s; here over "
     "the universal preset's viscosity at 10 /s"},
    {"universal", 5300, 0.5, 2e4, 0, 2100, 1e4, "composite", 6750 / 2.158, 19100 / 2.158,
     "a packable is 2.158 times a conventional composite (Lee, Son & Um, Dent Mater 2003) and packables 6.75 to "
     "19.1 kPa s (Loumprinis et al., Dent Mater 2021)"},
    {"packable", 11400, 0.5, 1e5, 0, 2200, 1.5e4, "composite", 6750, 19100,
     "Loumprinis et al., Dent Mater 2021: packables 6.75 to 19.1 kPa s at 23 C"},
    {"amalgam", 43000, 0.5, 2.3e5, 0, 11600, 1e4, "amalgam", 0, 0,
     "none: an amalgam's consistency is not published as a viscosity (assumed, for its ordering)"},
};

// The row of the preset `name`; std::invalid_argument naming the choices where there is none.
const PresetRow& preset_row(const std::string& name) {
  for (const PresetRow& r : kPresets)
    if (name == r.name) return r;
  throw std::invalid_argument(fmt::format("unknown material \"{}\"; choose {}", name, fmt::join(paste_preset_names(), ", ")));
}

}  // namespace

const std::vector<std::string>& paste_preset_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const PresetRow& r : kPresets) v.emplace_back(r.name);
    return v;
  }();
  return names;
}

real paste_temperature_factor(real temperature_c) {
  constexpr real kelvin = 273.15;
  return std::exp(kPasteActivation * (1 / (temperature_c + kelvin) - 1 / (23 + kelvin)));
}

PastePreset paste_preset(const std::string& name, real temperature_c) {
  if (!(temperature_c >= 10 && temperature_c <= 70))
    throw std::invalid_argument(fmt::format("a paste temperature of {} C is outside 10 to 70 C; give 23 (a room), 37 "
                                            "(the mouth) or 54 (a composite warmer)",
                                            temperature_c));
  const PresetRow& r = preset_row(name);
  PastePreset p;
  p.name = name;
  p.temperature_c = temperature_c;
  p.paste = composite(r.eta10, r.n, r.yield_stress, r.plateau, r.rho0, r.Kp);
  // The published ranges are at 23 C; warmer, the whole flow curve is lower by the same factor
  // (its consistency, yield stress and plateau).
  const real warm = paste_temperature_factor(temperature_c);
  p.paste.mu *= warm;
  p.paste.yield_stress *= warm;
  if (r.plateau > 0) p.paste.max_viscosity *= warm;
  p.cure = r.cure;
  p.published_low = r.low;
  p.published_high = r.high;
  p.source = r.source;
  if (r.ratio_high > 0) {
    p.published_ratio = std::array<real, 2>{r.ratio_low, r.ratio_high};
    p.ratio_source = r.ratio_source;
  }
  p.viscosity_at_10 = rheology::effective_viscosity(p.paste, 10);
  return p;
}

const std::vector<std::string>& instrument_surface_names() {
  static const std::vector<std::string> names{"steel", "coated"};
  return names;
}

real instrument_interface_strength(const std::string& surface) {
  if (surface == "steel") return 0;  // none of its own: the paste's kPasteSteelStrength holds
  if (surface == "coated") return kCoatedStrength;
  throw std::invalid_argument(
      fmt::format("unknown instrument surface \"{}\"; choose {}", surface, fmt::join(instrument_surface_names(), ", ")));
}

DentalSceneParams dental_params_for(const PastePreset& preset, DentalSceneParams dp) {
  // The paste with its contact's strength against the instrument (docs/model.md, "Tack"): paste
  // pulled past it slips off the instrument instead of being dragged along.
  dp.paste = preset.paste;
  dp.wall.Kp = 1.5 * preset.paste.Kp;
  dp.wall.rho0 = preset.paste.rho0;
  dp.iisph.viscosity_tolerance = 1e-3;
  dp.iisph.viscosity_iterations = 100;
  dp.iisph.pressure_solve = PressureSolve::cg;
  dp.iisph.max_iterations = 200;  // the universal's largest density error under 1% (docs/model.md, "Presets")
  dp.iisph.wall_rest_density = true;
  dp.iisph.viscous_pressure = kPresetViscousPressure;
  return dp;
}

void fill_scene_with(Scene& scene, const PastePreset& preset) {
  scene.force_scale = 1;
  scene.paste_preset = preset.name;
  scene.paste_temperature_c = preset.temperature_c;
}

std::string scene_paste_cure(const Scene& scene) {
  return scene.paste_preset.empty() ? "composite" : preset_row(scene.paste_preset).cure;
}

}  // namespace dentsph
