// A GPU backend's engine: a State's particles in the backend's memory, stepped with the tool pose
// in and the step's small results out. The CUDA build's (cuda_stepper.cpp) runs on a device, the
// emulation (emulator.cpp) runs the same stage bodies on the CPU. GpuStepper (gpu_stepper.cpp)
// makes either a Stepper. This header names no CUDA type.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "dentsph/step.hpp"

namespace dentsph::gpu {

class Engine {
 public:
  virtual ~Engine() = default;
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  // One step; the tool moves to `tool_pose`. step() is the haptic path: the pose goes in and the
  // results come out through one small copy each way, nothing else waits on the device.
  virtual void step(const Pose& tool_pose) = 0;
  // The same step with each stage timed (waiting for the device after each: slower; benchmarks).
  virtual void step_timed(const Pose& tool_pose, StageTimes& times) = 0;
  // Copies everything into `state`: particles in the backend's cell order, bonds, per-particle
  // results, and the small results (copy_results).
  virtual void download(State& state) const = 0;
  // Takes `state`, of the size this engine was made for, into the same memory (the CUDA graphs
  // stay captured) and sorts it as a new engine would.
  virtual void reload(const State& state) = 0;
  virtual std::string device_name() const = 0;

  // Particles the memory holds.
  std::uint32_t size() const { return size_; }
  // Copies only the step's small results into `state` (wrench, diagnostics, tool pose applied,
  // time, step count, bond counters).
  void copy_results(State& state) const;

 protected:
  explicit Engine(const Model& model) : dt_(model.dt) {}
  // The state a stepper starts from (at construction and at a reload), and each step's results.
  void start_from(const State& state);
  void finish_step(const ToolWrench& wrench, const StepDiagnostics& diagnostics, const BondCounters& counters,
                   const Pose& tool_pose);
  const Pose& tool_pose_applied() const { return tool_pose_applied_; }

 private:
  real dt_ = 0;
  std::uint32_t size_ = 0;
  ToolWrench wrench_;
  StepDiagnostics diagnostics_;
  BondCounters counters_;
  Pose tool_pose_applied_;
  std::uint64_t steps_ = 0;
  real time_ = 0;
};

// The CUDA engine (memory sized here, the step captured as a CUDA graph). Throws CudaUnavailable
// when the build has no CUDA backend or there is no device.
std::unique_ptr<Engine> make_cuda_engine(const Model& model, const State& state);
// The CUDA engine's algorithm on the CPU: the stage bodies looped over the particles, a stable
// sort for CUB's radix sort, sums for the reductions.
std::unique_ptr<Engine> make_emulated_engine(const Model& model, const State& state);

}  // namespace dentsph::gpu
