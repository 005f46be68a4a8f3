// The scene's dt against the limits its solver has (StepSolver::time_step_problem): the one check of
// the run, the runtime, the viewer and `dentsph validate`, and its message.
#include <fmt/format.h>

#include "dentsph/simulation.hpp"
#include "dentsph/solver.hpp"

namespace dentsph {

StabilityLimits check_time_step(const Scene& scene, const State& state, bool allow_unstable) {
  const StabilityLimits l = stability_limits(scene.model, state);
  if (allow_unstable) return l;
  const std::string problem =
      solver_properties(scene.model.solver).time_step_problem(scene.model, l, scene_tool_speed(scene));
  if (!problem.empty()) throw UnstableTimeStep(fmt::format("{}: {}", scene.source, problem));
  return l;
}

}  // namespace dentsph
