// What every backend shares: names, and the results a GpuStepper hands back each step.
#include "dentsph/backend.hpp"

#include <fmt/format.h>

namespace dentsph {

const char* backend_name(Backend b) { return b == Backend::cuda ? "cuda" : "cpu"; }

Backend parse_backend(const std::string& name) {
  if (name == "cpu") return Backend::cpu;
  if (name == "cuda") return Backend::cuda;
  throw std::invalid_argument(fmt::format("unknown backend '{}': choose cpu or cuda", name));
}

void GpuStepper::start_from(const Model& model, const State& state) {
  dt_ = model.dt;
  wrench_ = state.tool_wrench;
  diagnostics_ = state.diagnostics;
  counters_ = state.bonds.counters;
  tool_pose_applied_ = state.tool_pose_applied;
  steps_ = state.steps;
  time_ = state.time;
}

void GpuStepper::finish_step(const ToolWrench& wrench, const StepDiagnostics& diagnostics,
                             const BondCounters& counters, const Pose& tool_pose) {
  wrench_ = wrench;
  diagnostics_ = diagnostics;
  counters_ = counters;
  tool_pose_applied_ = tool_pose;
  time_ += dt_;
  ++steps_;
}

void GpuStepper::copy_results(State& state) const {
  state.tool_wrench = wrench_;
  state.diagnostics = diagnostics_;
  state.bonds.counters = counters_;
  state.tool_pose_applied = tool_pose_applied_;
  state.time = time_;
  state.steps = steps_;
}

}  // namespace dentsph
