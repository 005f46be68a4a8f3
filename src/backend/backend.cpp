// What every backend shares: names, the factory of steppers, and the results a GPU engine hands
// back each step.
#include "dentsph/backend.hpp"

#include <fmt/format.h>

#include "backend/cuda/engine.hpp"

namespace dentsph {

const char* backend_name(Backend b) {
  switch (b) {
    case Backend::cpu: return "cpu";
    case Backend::cuda: return "cuda";
    case Backend::cuda_emulation: return "cuda-emulation";
  }
  return "unknown";
}

Backend parse_backend(const std::string& name) {
  for (Backend b : {Backend::cpu, Backend::cuda, Backend::cuda_emulation})
    if (name == backend_name(b)) return b;
  throw std::invalid_argument(fmt::format("unknown backend '{}': choose cpu, cuda or cuda-emulation", name));
}

std::unique_ptr<Stepper> make_stepper(Backend backend, const Model& model, const State& state, int threads,
                                      ThreadPolicy policy) {
  // The GPU backends run the paper's step only.
  if (backend != Backend::cpu && model.solver != Solver::paper)
    throw std::invalid_argument(fmt::format(
        "--backend {}: the {} solver has no {} backend (the GPU backend has the paper's step only, and the scene's "
        "solver is {}); pass --solver paper to step the paper's model on the GPU, or leave out --backend to run the {} "
        "solver on the CPU",
        backend_name(backend), solver_name(model.solver), backend_name(backend), solver_name(model.solver),
        solver_name(model.solver)));
  switch (backend) {
    case Backend::cpu: return make_cpu_stepper(model, state, threads, policy);
    case Backend::cuda: return make_cuda_stepper(model, state);
    case Backend::cuda_emulation: return make_emulated_gpu_stepper(model, state);
  }
  throw std::invalid_argument("make_stepper: unknown backend");
}

namespace gpu {

void Engine::start_from(const State& state) {
  size_ = state.size();
  wrench_ = state.tool_wrench;
  diagnostics_ = state.diagnostics;
  counters_ = state.bonds.counters;
  tool_pose_applied_ = state.tool_pose_applied;
  steps_ = state.steps;
  time_ = state.time;
}

void Engine::finish_step(const ToolWrench& wrench, const StepDiagnostics& diagnostics, const BondCounters& counters,
                         const Pose& tool_pose) {
  wrench_ = wrench;
  diagnostics_ = diagnostics;
  counters_ = counters;
  tool_pose_applied_ = tool_pose;
  time_ += dt_;
  ++steps_;
}

void Engine::copy_results(State& state) const {
  state.tool_wrench = wrench_;
  state.diagnostics = diagnostics_;
  state.bonds.counters = counters_;
  state.tool_pose_applied = tool_pose_applied_;
  state.time = time_;
  state.steps = steps_;
}

}  // namespace gpu

}  // namespace dentsph
