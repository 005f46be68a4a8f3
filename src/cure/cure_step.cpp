// cure_between_steps: the one entry point of the curing (include/dentsph/cure.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/cure.hpp"

namespace dentsph {

CureModel make_cure_model(const Model& model, const CureMaterial& paste, real spacing, const Material& uncured) {
  if (!(spacing > 0)) throw std::invalid_argument(fmt::format("cure model: the spacing must be > 0 m, got {}", spacing));
  if (!(paste.alpha_max > 0) || !(paste.alpha_gel > 0) || !(paste.alpha_gel <= paste.alpha_max))
    throw std::invalid_argument(fmt::format("cure material \"{}\": needs 0 < alpha_gel <= alpha_max, got {} and {}",
                                            paste.name, paste.alpha_gel, paste.alpha_max));
  if (paste.light_cured && !(paste.dose_constant > 0))
    throw std::invalid_argument(fmt::format("cure material \"{}\": dose_constant must be > 0", paste.name));
  if (paste.self_setting && !(paste.set_time_constant > 0))
    throw std::invalid_argument(fmt::format("cure material \"{}\": set_time_constant must be > 0", paste.name));
  if (!(paste.shrinkage >= 0 && paste.shrinkage < 1))
    throw std::invalid_argument(fmt::format("cure material \"{}\": shrinkage must be in [0, 1)", paste.name));
  CureModel cm;
  cm.paste = paste;
  cm.spacing = spacing;
  // The viscous limit dt <= 0.125 h^2 rho0 / mu (docs/model.md, "Stability"), kept at half of it: rho0 is
  // the bulk's, and the pair terms of a particle at the surface, at a third of it, are up to ten
  // times the bulk's (m_j / rho_j and 1 / rho_i). At 0.8 of it, two surface particles of a cured
  // filling's second increment (rho 625 of 2000, mu 1.42 Pa s, adhesion risen 5%, dt 50 us) grew
  // an oscillation 1.4x a step 5 ms after the light came on and flung 45 particles out of the
  // cavity; at half of it (0.9 Pa s, under the paste's own 1 Pa s) nothing was lost.
  // A paste with a flow law (an SI preset) is stepped only by the iisph solver, whose viscosity is
  // implicit (stable at any viscosity): its setting is not capped.
  const real h = model.kernel.h;
  cm.viscosity_limit = newtonian(uncured) ? 0.5 * 0.125 * h * h * uncured.rho0 / model.dt
                                          : std::numeric_limits<real>::infinity();
  cm.shrink_tolerance = 0.01 * spacing;
  return cm;
}

namespace {

bool same_light(const CuringLight& a, const CuringLight& b) {
  return a.tip == b.tip && a.direction == b.direction && a.diameter == b.diameter && a.irradiance == b.irradiance &&
         a.on == b.on;
}

// The conversion of every paste particle from its dose and age, and its parameters from it.
std::uint32_t update_conversion(const CureModel& cm, State& s) {
  CureState& c = s.cure;
  const CureMaterial& m = cm.paste;
  std::uint32_t converted = 0;
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t id = s.id[i];
    if (!c.curable[id]) continue;
    const real alpha = std::max(conversion_from_dose(m, c.dose[id]), conversion_from_age(m, s.time - c.mixed_at[id]));
    if (!(alpha > c.alpha[id])) continue;
    c.alpha[id] = alpha;
    const Material p = cured_parameters(m, {c.mu0[id], c.Kp0[id], c.rho00[id], c.Ka0[id]}, alpha, cm.viscosity_limit);
    s.mu[i] = p.mu;
    s.Kp[i] = p.Kp;
    s.rho0[i] = p.rho0;
    s.Ka[i] = p.Ka;
    c.set_cured(id, p);  // kept by id: the reorder and refresh_materials rewrite s.mu... from it
    s.material[i] |= kCuredMaterial;
    ++converted;
  }
  return converted;
}

}  // namespace

namespace {

bool light_reaches(const CureModel& cm, const std::optional<CuringLight>& light) {
  return light && light->on && light->irradiance > 0 && cm.paste.light_cured;
}

}  // namespace

bool cure_pass_due(const CureModel& cm, const State& s, const std::optional<CuringLight>& light) {
  return light_reaches(cm, light) != s.cure.light_on || s.time >= s.cure.next_pass;
}

CureUpdate cure_between_steps(const CureModel& cm, State& s, const std::optional<CuringLight>& light, real dt) {
  CureState& c = s.cure;
  const CureMaterial& m = cm.paste;
  CureUpdate up;
  const bool lit = light_reaches(cm, light);
  // A light turned on or off: a pass now. A light that moved (a hand-held light follows the hand):
  // the next pass, within an interval, takes its new place.
  if (lit != c.light_on) {
    c.light_on = lit;
    c.next_pass = std::min(c.next_pass, s.time);
    if (!lit) {
      std::fill(c.irradiance.begin(), c.irradiance.end(), real(0));
      c.lit_ids.clear();
      c.lit_irradiance.clear();
    }
  }
  if (lit && !same_light(*light, c.light)) {
    c.light = *light;
    c.next_pass = std::min(c.next_pass, s.time + cm.transition_interval);
  }
  const bool pass = s.time >= c.next_pass;
  if (pass && lit) compute_irradiance(cm, s, *light);
  // Every step: the dose, from the irradiance of the last transport.
  up.lit = std::uint32_t(c.lit_ids.size());
  for (std::size_t k = 0; k < c.lit_ids.size(); ++k) c.dose[c.lit_ids[k]] += c.lit_irradiance[k] * dt;
  if (!pass) return up;
  // The pass: conversion, parameters, gel transition and shrinkage.
  up.converted = update_conversion(cm, s);
  const CureUpdate t = apply_cure_transition(cm, s);
  up.set = t.set;
  up.moved = t.moved;
  // The next pass after an interval while anything can change, else when a light comes on.
  const bool active = lit || m.self_setting || up.converted > 0 || up.set > 0 || up.moved;
  c.next_pass = active ? s.time + cm.transition_interval : std::numeric_limits<real>::infinity();
  return up;
}

}  // namespace dentsph
