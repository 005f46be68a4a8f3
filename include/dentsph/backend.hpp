// Backends of the step: the CPU (step(), src/step) and the GPU (CUDA, src/backend/cuda). The GPU
// backend keeps the particles in device memory between steps: a GpuStepper uploads a State once,
// steps it with the tool pose in and the tool wrench out, and downloads the particles when a
// consumer needs them. This header names no CUDA type; a build without CUDA has it too and says
// why the CUDA backend is missing (docs/cuda.md).
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

// cuda_emulation: the CUDA backend's algorithm run on the CPU (make_emulated_gpu_stepper), so that
// the GPU path of the run loop and the benchmark is exercised where there is no GPU; slow.
enum class Backend { cpu, cuda, cuda_emulation };
const char* backend_name(Backend b);
// "cpu", "cuda" or "cuda-emulation"; anything else throws std::invalid_argument naming the choices.
Backend parse_backend(const std::string& name);

// Whether the CUDA backend can run here: built with CUDA, and a device present. `reason` says why
// not ("this build has no CUDA backend: ..." or "no CUDA device: ..."); `device` names the GPU.
struct CudaStatus {
  bool available = false;
  std::string reason;
  std::string device;
};
CudaStatus cuda_status();
// Whether this build compiled the CUDA backend (it may still find no device).
bool cuda_built();

// The CUDA backend is unavailable (what() says why, as CudaStatus::reason).
class CudaUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A State stepped on the GPU. step() is the haptic path: the pose goes in and the wrench comes out
// through one small copy each way, nothing else waits on the device.
class GpuStepper {
 public:
  virtual ~GpuStepper() = default;
  // One step; the tool moves to `tool_pose`. Afterwards wrench() and diagnostics() are this step's.
  virtual void step(const Pose& tool_pose) = 0;
  // The same step with each stage timed (waiting for the device after each: slower; benchmarks).
  virtual void step_timed(const Pose& tool_pose, StageTimes& times) = 0;
  // Copies everything into `state`: particles in the GPU's cell order, bonds, per-particle results,
  // the wrench, diagnostics, time and step count.
  virtual void download(State& state) const = 0;
  virtual std::string device_name() const = 0;

  // Copies only the step's small results into `state` (wrench, diagnostics, tool pose, time, step
  // count, bond counters): what the run loop reads every step, without moving the particles.
  void copy_results(State& state) const;
  const ToolWrench& wrench() const { return wrench_; }
  const StepDiagnostics& diagnostics() const { return diagnostics_; }
  const BondCounters& bond_counters() const { return counters_; }
  std::uint64_t steps() const { return steps_; }
  real time() const { return time_; }

 protected:
  // For the implementations: the state a stepper starts from, and each step's results.
  void start_from(const Model& model, const State& state);
  void finish_step(const ToolWrench& wrench, const StepDiagnostics& diagnostics, const BondCounters& counters,
                   const Pose& tool_pose);

  real dt_ = 0;
  ToolWrench wrench_;
  StepDiagnostics diagnostics_;
  BondCounters counters_;
  Pose tool_pose_applied_;
  std::uint64_t steps_ = 0;
  real time_ = 0;
};

// The CUDA stepper for `state` under `model` (memory sized here, the step captured as a CUDA
// graph). Throws CudaUnavailable when the build has no CUDA backend or there is no device.
std::unique_ptr<GpuStepper> make_cuda_stepper(const Model& model, const State& state);
// The same algorithm run on the CPU: the CUDA backend's stage bodies looped over the particles,
// a stable sort for CUB's radix sort, sums for the reductions. Always built; tested against step().
std::unique_ptr<GpuStepper> make_emulated_gpu_stepper(const Model& model, const State& state);
// The stepper of a GPU backend (cuda or cuda_emulation).
std::unique_ptr<GpuStepper> make_gpu_stepper(Backend backend, const Model& model, const State& state);

}  // namespace dentsph
