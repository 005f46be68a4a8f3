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
  // The viscous limit dt <= 0.125 h^2 rho0 / mu (MODEL.md, "Stability"), kept at 0.8 of it.
  const real h = model.kernel.h;
  cm.viscosity_limit = 0.8 * 0.125 * h * h * uncured.rho0 / model.dt;
  cm.shrink_tolerance = 0.01 * spacing;
  return cm;
}

CureUpdate cure_between_steps(const CureModel& cm, State& s, const std::optional<CuringLight>& light, real dt) {
  CureState& c = s.cure;
  const CureMaterial& m = cm.paste;
  CureUpdate up;
  const bool lit = light && light->on && light->irradiance > 0 && m.light_cured;
  // Nothing to do without light or setting, once the last transition has been applied.
  const bool due = s.time >= c.next_transition;
  if (!lit && !m.self_setting && !due) return up;

  if (lit) up.lit = compute_irradiance(cm, s, *light);
  if (lit || m.self_setting) {
    const std::uint32_t n = s.size();
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t id = s.id[i];
      if (!c.curable[id]) continue;
      if (lit) c.dose[id] += c.irradiance[id] * dt;
      const real alpha = std::max(conversion_from_dose(m, c.dose[id]), conversion_from_age(m, s.time - c.mixed_at[id]));
      if (!(alpha > c.alpha[id])) continue;
      c.alpha[id] = alpha;
      const Material p = cured_parameters(m, {c.mu0[id], c.Kp0[id], c.rho00[id], c.Ka0[id]}, alpha, cm.viscosity_limit);
      s.mu[i] = p.mu;
      s.Kp[i] = p.Kp;
      s.rho0[i] = p.rho0;
      s.Ka[i] = p.Ka;
      ++up.converted;
    }
    // A conversion that rose makes the next transition pass due (at most every interval).
    if (up.converted > 0 && c.next_transition > s.time + cm.transition_interval)
      c.next_transition = s.time + cm.transition_interval;
  } else if (!lit) {
    // No light any more: zero what the last lit update left.
    std::fill(c.irradiance.begin(), c.irradiance.end(), real(0));
  }
  if (s.time >= c.next_transition) {
    const CureUpdate t = apply_cure_transition(cm, s);
    up.set = t.set;
    up.moved = t.moved;
    // The next pass: after an interval while anything converts or moves, else when conversion
    // next rises (set above).
    c.next_transition = (up.converted > 0 || t.set > 0 || t.moved) ? s.time + cm.transition_interval
                                                                     : std::numeric_limits<real>::infinity();
  }
  return up;
}

}  // namespace dentsph
