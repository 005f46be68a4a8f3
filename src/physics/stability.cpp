// Time-step limits (MODEL.md, "Stability"). Kp has the units of a squared sound speed
// (dP/drho = Kp), so c = sqrt(max Kp) over every particle that can push material. The iisph solver
// (src/solver) is implicit in pressure and viscosity: its step is limited by the velocity CFL
// condition alone.
#include <algorithm>
#include <cmath>
#include <limits>

#include "dentsph/step.hpp"

namespace dentsph {

namespace {

constexpr real inf = std::numeric_limits<real>::infinity();

}  // namespace

StabilityLimits stability_limits(const Model& model, const State& s, const Material* paste) {
  const real h = model.kernel.h;
  real kp_max = 0, rho_over_mu_min = inf;
  // The particles `paste` would change: those of the Model's paste material the cure has left as
  // they were (or, where the Model names no paste, every material particle).
  const std::optional<MaterialIndex> paste_index = model.materials.paste;
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    const bool edited = paste && (paste_index ? s.material[i] == *paste_index : s.role[i] == Role::material);
    const real Kp = edited ? paste->Kp : s.Kp[i], mu = edited ? paste->mu : s.mu[i];
    const real rho0 = edited ? paste->rho0 : s.rho0[i];
    kp_max = std::max(kp_max, Kp);
    if (mu > 0) rho_over_mu_min = std::min(rho_over_mu_min, rho0 / mu);
  }
  StabilityLimits l;
  l.paper_acoustic = kp_max > 0 ? model.cfl_lambda * h / std::sqrt(kp_max) : inf;
  l.paper_viscous = 0.125 * h * h * rho_over_mu_min;
  l.force = force_time_step_limit(model, s.diagnostics);
  if (model.solver == Solver::iisph) {
    l.acoustic = inf;
    l.viscous = inf;
    l.sound_speed = h / model.dt;
  } else {
    l.acoustic = l.paper_acoustic;
    l.viscous = l.paper_viscous;
    l.sound_speed = std::sqrt(kp_max);
  }
  return l;
}

real velocity_time_step_limit(const Model& model, real speed) {
  return speed > 0 ? model.iisph.cfl * model.kernel.h / speed : inf;
}

real force_time_step_limit(const Model& model, const StepDiagnostics& d) {
  if (model.solver == Solver::iisph) return velocity_time_step_limit(model, d.max_speed);
  return d.max_accel > 0 ? 0.25 * std::sqrt(model.kernel.h / d.max_accel) : inf;
}

}  // namespace dentsph
