// The CUDA backend's kernel launches, one per stage (each .cu file of this folder holds its stage's
// kernel: a thin loop over the stage body of the matching .hpp). Plain C++: the host code that
// calls them (cuda_stepper.cpp) needs no nvcc. Each returns the launch's error (cudaGetLastError).
#pragma once

#include <cstddef>

#include <cuda_runtime_api.h>

#include "backend/cuda/view.hpp"

namespace dentsph::gpu {

// Device scratch of CUB's radix sort, sized once (sort_scratch_bytes).
struct SortScratch {
  void* ptr = nullptr;
  std::size_t bytes = 0;
};

cudaError_t launch_hash(const StepView& v, cudaStream_t s);
std::size_t sort_scratch_bytes(const StepView& v);
// Radix sort of the keys, then each bucket's range (the bucket arrays zeroed first).
cudaError_t launch_sort(const StepView& v, const SortScratch& scratch, cudaStream_t s);
cudaError_t launch_reorder(const StepView& v, cudaStream_t s);
cudaError_t launch_static_density(const StepView& v, cudaStream_t s);
cudaError_t launch_density(const StepView& v, cudaStream_t s);
cudaError_t launch_pressure(const StepView& v, cudaStream_t s);
cudaError_t launch_forces(const StepView& v, cudaStream_t s);
// Per-block partial sums of the wrench (partials [0, blocks)).
cudaError_t launch_tool_wrench(const StepView& v, cudaStream_t s);
// Integration, its per-block diagnostics (partials [blocks, 2 blocks)), and the step's output.
cudaError_t launch_integrate(const StepView& v, cudaStream_t s);
cudaError_t launch_finish(const StepView& v, cudaStream_t s);

// The whole step in the paper's order (step.cu). With `marks` (9 events), an event is recorded
// before the first stage and after each of hash, sort, reorder, density, pressure, forces, wrench
// and integrate, for the stage times.
cudaError_t enqueue_step(const StepView& v, const SortScratch& scratch, cudaStream_t s, cudaEvent_t* marks = nullptr);

}  // namespace dentsph::gpu
