// A GPU engine (the CUDA backend or its emulation) as a Stepper: the host State receives the small
// results every step and the particles on demand, once at most between two steps; a State handed
// back at its size goes into the same memory (the CUDA graphs stay captured), at another size
// into a new engine.
#include <memory>

#include "backend/cuda/engine.hpp"
#include "dentsph/backend.hpp"

namespace dentsph {

namespace {

using MakeEngine = std::unique_ptr<gpu::Engine> (*)(const Model&, const State&);

class GpuStepper final : public Stepper {
 public:
  GpuStepper(Backend backend, MakeEngine make, const Model& model, const State& state)
      : backend_(backend), make_(make), model_(model), engine_(make(model, state)) {}

  const char* name() const override { return backend_name(backend_); }
  std::string device_name() const override { return engine_->device_name(); }

  void step(State& host, const Pose& tool_pose) override {
    engine_->step(tool_pose);
    finish(host, tool_pose);
  }
  void step_timed(State& host, const Pose& tool_pose, StageTimes& times) override {
    engine_->step_timed(tool_pose, times);
    finish(host, tool_pose);
  }
  void sync_to_host(State& host) override {
    if (synced_ == &host) return;  // nothing stepped since this State was last written
    engine_->download(host);
    synced_ = &host;
  }
  void sync_from_host(const State& host) override {
    if (host.size() == engine_->size())
      engine_->reload(host);
    else
      engine_ = make_(model_, host);
    synced_ = nullptr;  // the engine sorted the particles anew
  }

 private:
  void finish(State& host, const Pose& tool_pose) {
    engine_->copy_results(host);
    host.tool_pose = tool_pose;
    synced_ = nullptr;
  }

  Backend backend_;
  MakeEngine make_;
  const Model& model_;  // the caller's (a Simulation's): it outlives the stepper
  std::unique_ptr<gpu::Engine> engine_;
  const State* synced_ = nullptr;  // the State whose particles are the engine's now
};

}  // namespace

// The GPU backends run the paper's explicit step (the stage bodies of src/backend/cuda). When the
// Model gains a choice of solver, these two factories are where a GPU stepper refuses a solver it
// lacks (std::invalid_argument naming the solver and the backends that have it).

std::unique_ptr<Stepper> make_cuda_stepper(const Model& model, const State& state) {
  return std::make_unique<GpuStepper>(Backend::cuda, &gpu::make_cuda_engine, model, state);
}

std::unique_ptr<Stepper> make_emulated_gpu_stepper(const Model& model, const State& state) {
  return std::make_unique<GpuStepper>(Backend::cuda_emulation, &gpu::make_emulated_engine, model, state);
}

}  // namespace dentsph
