// Backends of the step, each a Stepper (stepper.hpp): the CPU (step(), src/step) and the GPU (CUDA,
// src/backend/cuda, and its emulation on the CPU). The GPU backend keeps the particles in device
// memory between steps: its stepper uploads a State once, steps it with the tool pose in and the
// small results out, and downloads the particles when a consumer needs them. This header names no
// CUDA type; a build without CUDA has it too and says why the CUDA backend is missing
// (docs/cuda.md).
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "dentsph/step.hpp"
#include "dentsph/stepper.hpp"

namespace dentsph {

// cuda_emulation: the CUDA backend's algorithm run on the CPU (make_emulated_gpu_stepper), so that
// the GPU path of every loop (offline run, realtime runtime, viewer, replay) and of the benchmark is
// exercised where there is no GPU; slow.
enum class Backend { cpu, cuda, cuda_emulation };
const char* backend_name(Backend b);
// "cpu", "cuda" or "cuda-emulation"; anything else throws std::invalid_argument naming the choices.
Backend parse_backend(const std::string& name);

// How closely a GPU backend (or its emulation) agrees with the CPU step: the particles after a
// hundred steps relative to each value (or to a small share of the field's largest where values
// are small; tests/parity, tests/cuda), and the tool forces of a recorded session replayed on
// another backend relative to the session's peak force (compare_replay: dentsph replay,
// tests/haptics). They differ only in the order of summation.
inline constexpr real kBackendParityTolerance = 1e-4;
// The least force (N) that the replay's tolerance is taken relative to: a session whose tool
// touched nothing records forces of the size of rounding (about 1e-32 N), which two summation
// orders change entirely; a force under 1e-9 N is 1.5e-5 N on a device at the dental scenes'
// force scale.
inline constexpr real kBackendParityForceFloor = 1e-9;

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

// The CUDA stepper for `state` under `model` (memory sized here, the step captured as a CUDA
// graph). Throws CudaUnavailable when the build has no CUDA backend or there is no device.
std::unique_ptr<Stepper> make_cuda_stepper(const Model& model, const State& state);
// The same algorithm run on the CPU: the CUDA backend's stage bodies looped over the particles,
// a stable sort for CUB's radix sort, sums for the reductions. Always built; tested against step().
std::unique_ptr<Stepper> make_emulated_gpu_stepper(const Model& model, const State& state);
// The stepper of `backend` for `state` under `model` (the caller's, outliving the stepper, which
// reads it by reference); `threads` are the CPU step's. Throws
// CudaUnavailable for cuda where it cannot run, and std::invalid_argument for a model the backend
// cannot step.
std::unique_ptr<Stepper> make_stepper(Backend backend, const Model& model, const State& state, int threads,
                                      ThreadPolicy policy = ThreadPolicy::fixed);

}  // namespace dentsph
