// The acoustic and viscous limits against dt: the one check of the run, the runtime, the viewer
// and `dentsph validate`, and its message.
#include <algorithm>

#include <fmt/format.h>

#include "dentsph/simulation.hpp"

namespace dentsph {

std::string time_step_excess(real dt, const StabilityLimits& l) {
  const real limit = std::min(l.acoustic, l.viscous);
  if (!(dt > limit)) return "";
  const char* which = l.acoustic <= l.viscous ? "acoustic (lambda h / sqrt(max stiffness))"
                                              : "viscous (0.125 h^2 rest_density / viscosity)";
  return fmt::format("simulation.dt: {:.3g} s is over the {} stability limit of {:.3g} s (acoustic {:.3g} s, viscous "
                     "{:.3g} s)",
                     dt, which, limit, l.acoustic, l.viscous);
}

StabilityLimits check_time_step(const Scene& scene, const State& state, bool allow_unstable) {
  const StabilityLimits l = stability_limits(scene.model, state);
  const real dt = scene.model.dt;
  if (scene.model.solver == Solver::iisph) {
    // The velocity CFL condition, against the fastest the scene's tool moves (the material moves
    // with it or slower; a device's hand is checked as it goes, by the force limit entry).
    const real v = scene_tool_speed(scene), limit = velocity_time_step_limit(scene.model, v);
    if (dt > limit && !allow_unstable)
      throw UnstableTimeStep(fmt::format(
          "{}: simulation.dt: {:.3g} s is over the iisph solver's velocity CFL limit of {:.3g} s (cfl {:.3g} * h {:.3g} m "
          "/ {:.3g} m/s, the tool's fastest speed between its keyframes); set simulation.dt to at most {:.3g}, slow "
          "the tool, or pass --allow-unstable to run anyway",
          scene.source, dt, limit, scene.model.iisph.cfl, scene.model.kernel.h, v, limit));
    return l;
  }
  const std::string excess = time_step_excess(scene.model.dt, l);
  if (!excess.empty() && !allow_unstable)
    throw UnstableTimeStep(fmt::format("{}: {}; set simulation.dt to at most {:.3g}, lower the stiffest material's "
                                       "stiffness or viscosity, choose the iisph solver (simulation.solver, --solver iisph), or "
                                       "pass --allow-unstable to run anyway",
                                       scene.source, excess, std::min(l.acoustic, l.viscous)));
  return l;
}

}  // namespace dentsph
