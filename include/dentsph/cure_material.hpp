// How a filling material sets (docs/model.md, "Curing"): by light (a composite: its degree of
// conversion rises with the radiant exposure it receives) or by itself over time (an amalgam:
// after a working time), and what its conversion does to the paste's parameters. One mapping,
// cured_parameters(), turns a conversion into viscosity, adhesion and rest density; past the gel
// point the paste no longer flows and is made rigid (src/cure/transition.cpp).
#pragma once

#include <string>
#include <vector>

#include "dentsph/state.hpp"

namespace dentsph {

struct CureMaterial {
  std::string name;
  // ---- conversion ----------------------------------------------------------------------------
  real alpha_max = 0.60;        // largest degree of conversion
  real alpha_gel = 0.018;       // conversion at the gel point: past it the paste is rigid
  // Light: alpha = alpha_max (1 - exp(-H / dose_constant)), H the radiant exposure received.
  bool light_cured = true;
  real dose_constant = 1e4;     // J/m^2 (1e4 = 1 J/cm^2)
  // Setting by itself: alpha = alpha_max (1 - exp(-(age - working_time) / set_time_constant))
  // once the paste is older than working_time (age: time since it was mixed, i.e. added).
  bool self_setting = false;
  real working_time = 0;        // s
  real set_time_constant = 0;   // s
  // ---- light transport -----------------------------------------------------------------------
  // Beer-Lambert attenuation coefficient of the paste, falling linearly with alpha / alpha_max
  // from the uncured to the cured value (the photoinitiator bleaches, the resin's refractive index
  // comes closer to the filler's).
  real attenuation_uncured = 1150;  // 1/m (1.15 per mm: 10% transmitted through 2 mm)
  real attenuation_cured = 1000;    // 1/m
  // ---- the paste's parameters (cured_parameters) ---------------------------------------------
  real viscosity_factor_at_gel = 10;  // mu(alpha_gel) / mu(0), before the time step's limit
  real adhesion_factor_at_gel = 2;    // Ka(alpha_gel) / Ka(0)
  real shrinkage = 0.025;             // volumetric shrinkage at alpha_max (mass kept)
};

// The presets, by name: "composite" (a conventional universal composite), "amalgam".
CureMaterial cure_material_preset(const std::string& name);
const std::vector<std::string>& cure_material_presets();

// The published value a preset's depth of cure is checked against (docs/model.md).
struct PublishedDepthOfCure {
  real depth = 0;          // m, ISO 4049 depth of cure (half the cured length)
  real irradiance = 0;     // W/m^2 of the light used
  real exposure_time = 0;  // s
  std::string source;      // where it was published
};
// The preset's published ISO 4049 depth of cure; depth 0 when it has none (a material that is not
// light-cured).
PublishedDepthOfCure published_depth_of_cure(const std::string& preset);

// ---- the laws ---------------------------------------------------------------------------------

// Conversion after a radiant exposure `dose` (J/m^2); 0 for a material that is not light-cured.
real conversion_from_dose(const CureMaterial& m, real dose);
// Conversion of a self-setting material `age` seconds after mixing; 0 for one that is not.
real conversion_from_age(const CureMaterial& m, real age);
// The age (s after mixing) at which a self-setting material reaches its gel point (rigid):
// conversion_from_age's inverse at alpha_gel; infinity for one that is not self-setting.
real gel_age(const CureMaterial& m);
// Attenuation coefficient (1/m) of the paste at conversion alpha.
real paste_attenuation(const CureMaterial& m, real alpha);

// The factor on the paste's viscosity at conversion `alpha`: viscosity_factor_at_gel^(alpha /
// alpha_gel), the gel point's factor past it (uncapped: cured_parameters caps it). For a paste with a
// flow law the factor raises its whole flow curve (docs/model.md, "Presets").
real setting_viscosity_factor(const CureMaterial& m, real alpha);
// The paste's parameters at conversion `alpha`, from its uncured ones: viscosity and adhesion
// rise geometrically with alpha / alpha_gel up to their factors at the gel point (the viscosity no
// higher than `viscosity_limit`, the largest the time step allows, and never lowered by it), the
// rest density rises as the paste shrinks, rho0 / (1 - shrinkage alpha / alpha_max), the mass
// kept; Kp is kept. The one mapping from conversion to parameters (a material table in the Model
// will call it).
Material cured_parameters(const CureMaterial& m, const Material& uncured, real alpha, real viscosity_limit);

}  // namespace dentsph
