// Time-step limits (docs/model.md, "Stability"). Kp has the units of a squared sound speed
// (dP/drho = Kp), so c = sqrt(max Kp) over every particle that can push material. Which of them bind
// is the model's solver's to say (StepSolver::set_limits, motion_limit): the paper's explicit step
// has all of them, the iisph solver (implicit in pressure and viscosity) the velocity CFL condition
// alone.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "dentsph/solver.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

namespace {

constexpr real inf = std::numeric_limits<real>::infinity();

}  // namespace

StabilityLimits stability_limits(const Model& model, const State& s, const Material* paste) {
  const real h = model.kernel.h;
  real kp_max = 0, rho_over_mu_min = inf, rho0_min = inf, mu_min = inf;
  // The particles `paste` would change: those of the Model's paste material the cure has left as
  // they were (or, where the Model names no paste, every material particle).
  const std::optional<MaterialIndex> paste_index = model.materials.paste;
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    const bool edited = paste && (paste_index ? s.material[i] == *paste_index : s.role[i] == Role::material);
    const real Kp = edited ? paste->Kp : s.Kp[i], mu = edited ? paste->mu : s.mu[i];
    const real rho0 = edited ? paste->rho0 : s.rho0[i];
    kp_max = std::max(kp_max, Kp);
    if (mu > 0) rho_over_mu_min = std::min(rho_over_mu_min, rho0 / mu);
    if (s.role[i] == Role::material) {
      rho0_min = std::min(rho0_min, rho0);
      mu_min = std::min(mu_min, mu);
    }
  }
  StabilityLimits l;
  l.paper_acoustic = kp_max > 0 ? model.cfl_lambda * h / std::sqrt(kp_max) : inf;
  l.paper_viscous = 0.125 * h * h * rho_over_mu_min;
  l.force = force_time_step_limit(model, s.diagnostics);
  const real sigma = model.iisph.surface_tension;
  if (sigma > 0 && rho0_min < inf)
    l.capillary = std::max(std::sqrt(rho0_min * h * h * h / (2 * std::numbers::pi * sigma)), mu_min * h / sigma);
  solver_properties(model.solver).set_limits(model, kp_max, l);
  return l;
}

real velocity_time_step_limit(const Model& model, real speed) {
  return speed > 0 ? model.iisph.cfl * model.kernel.h / speed : inf;
}

real force_time_step_limit(const Model& model, const StepDiagnostics& d) {
  return solver_properties(model.solver).motion_limit(model, d);
}

std::string time_step_excess(real dt, const StabilityLimits& l) {
  const real limit = std::min(l.acoustic, l.viscous);
  if (!(dt > limit)) return "";
  const char* which = l.acoustic <= l.viscous ? "acoustic (lambda h / sqrt(max stiffness))"
                                              : "viscous (0.125 h^2 rest_density / viscosity)";
  return fmt::format("simulation.dt: {:.3g} s is over the {} stability limit of {:.3g} s (acoustic {:.3g} s, viscous "
                     "{:.3g} s)",
                     dt, which, limit, l.acoustic, l.viscous);
}

}  // namespace dentsph
