// Cure materials: presets, the conversion laws and the one mapping from conversion to the paste's
// parameters (include/dentsph/cure_material.hpp; constants and sources in docs/model.md, "Curing").
#include "dentsph/cure_material.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace dentsph {

const std::vector<std::string>& cure_material_presets() {
  static const std::vector<std::string> names = {"composite", "amalgam"};
  return names;
}

CureMaterial cure_material_preset(const std::string& name) {
  CureMaterial m;
  m.name = name;
  if (name == "composite") {
    // A conventional universal composite (a Bis-GMA/UDMA hybrid such as Filtek Z250, shade A3).
    // alpha_max: a typical final conversion of such composites. dose_constant: 1 J/cm^2, so that
    // 16 J/cm^2 at the top leaves 0.8 of the top's conversion about 2 mm down (the 2 mm rule).
    // Attenuation: 1.15 per mm uncured (10% through 2 mm), 1.0 per mm cured. alpha_gel: the one
    // constant fitted, to the published ISO 4049 depth of cure (published_depth_of_cure).
    m.alpha_max = 0.60;
    m.alpha_gel = 0.018;  // 3% of alpha_max
    m.light_cured = true;
    m.dose_constant = 1e4;
    m.attenuation_uncured = 1150;
    m.attenuation_cured = 1000;
    m.viscosity_factor_at_gel = 10;
    m.adhesion_factor_at_gel = 2;
    m.shrinkage = 0.025;
    return m;
  }
  if (name == "amalgam") {
    // An amalgam: sets by itself after a working time, whatever the light; opaque; no shrinkage to
    // speak of. alpha is the degree of set (0 to 1); past half of it the paste is rigid.
    m.alpha_max = 1;
    m.alpha_gel = 0.5;
    m.light_cured = false;
    m.self_setting = true;
    m.working_time = 180;
    m.set_time_constant = 240;
    m.attenuation_uncured = 1e5;
    m.attenuation_cured = 1e5;
    m.viscosity_factor_at_gel = 10;
    m.adhesion_factor_at_gel = 1;
    m.shrinkage = 0;
    return m;
  }
  throw std::invalid_argument(
      fmt::format("unknown material \"{}\"; known: {}", name, fmt::join(cure_material_presets(), ", ")));
}

PublishedDepthOfCure published_depth_of_cure(const std::string& preset) {
  if (preset == "composite")
    return {3.0e-3, 1e4, 20,
            "NIOM, ISO 4049 depth of cure of Filtek Z250 A3 cured 20 s in contact with LED lights on their "
            "high-power settings: 3.0 to 3.1 mm (niom.no, 'Composite depth of cure and LED dental curing lamp "
            "characteristics', Table 1)"};
  return {};
}

real conversion_from_dose(const CureMaterial& m, real dose) {
  if (!m.light_cured || !(dose > 0)) return 0;
  return m.alpha_max * -std::expm1(-dose / m.dose_constant);
}

real conversion_from_age(const CureMaterial& m, real age) {
  if (!m.self_setting || !(age > m.working_time)) return 0;
  return m.alpha_max * -std::expm1(-(age - m.working_time) / m.set_time_constant);
}

real gel_age(const CureMaterial& m) {
  if (!m.self_setting) return std::numeric_limits<real>::infinity();
  return m.working_time - m.set_time_constant * std::log1p(-m.alpha_gel / m.alpha_max);
}

real paste_attenuation(const CureMaterial& m, real alpha) {
  const real f = std::clamp(alpha / m.alpha_max, real(0), real(1));
  return m.attenuation_uncured + (m.attenuation_cured - m.attenuation_uncured) * f;
}

namespace {

// A factor rising geometrically with alpha / alpha_gel from 1 to `at_gel`, and `at_gel` past the gel
// point (no pow: most calls, the paste set).
real toward_gel(const CureMaterial& m, real alpha, real at_gel) {
  const real to_gel = std::clamp(alpha / m.alpha_gel, real(0), real(1));
  return to_gel >= 1 ? at_gel : std::pow(at_gel, to_gel);
}

}  // namespace

real setting_viscosity_factor(const CureMaterial& m, real alpha) {
  return toward_gel(m, alpha, m.viscosity_factor_at_gel);
}

Material cured_parameters(const CureMaterial& m, const Material& uncured, real alpha, real viscosity_limit) {
  Material p = uncured;
  p.mu = uncured.mu * setting_viscosity_factor(m, alpha);
  p.mu = std::min(p.mu, std::max(uncured.mu, viscosity_limit));
  p.Ka = uncured.Ka * toward_gel(m, alpha, m.adhesion_factor_at_gel);
  p.rho0 = uncured.rho0 / (1 - m.shrinkage * std::clamp(alpha / m.alpha_max, real(0), real(1)));
  return p;
}

}  // namespace dentsph
