// Stage 6 on the device: integration with per-block diagnostics (partials [blocks, 2 blocks)), and
// the step's output: one block adds every partial in a fixed order.
#include "backend/cuda/integrate.hpp"
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"

namespace dentsph::gpu {

__global__ void integrate_kernel(StepView v) {
  const std::uint32_t i = thread_index();
  block_sum(i < v.n ? integrate_body(v, i) : StepSums{}, v.partials + blocks_for(v.n));
}

// One block: each thread adds a strided share of the partials, then the block's tree.
__global__ void finish_kernel(StepView v) {
  StepSums mine;
  for (std::uint32_t b = threadIdx.x; b < v.partial_count; b += kBlock) mine.add(v.partials[b]);
  __shared__ alignas(StepSums) unsigned char raw[sizeof(StepSums)];
  StepSums* total = reinterpret_cast<StepSums*>(raw);
  block_sum(mine, total);
  __syncthreads();
  if (threadIdx.x == 0) {
    v.out->sums = *total;
    v.out->events = *v.events;
  }
}

cudaError_t launch_integrate(const StepView& v, cudaStream_t s) {
  integrate_kernel<<<grid_for(v.n), kBlock, 0, s>>>(v);
  return cudaGetLastError();
}

cudaError_t launch_finish(const StepView& v, cudaStream_t s) {
  finish_kernel<<<1, kBlock, 0, s>>>(v);
  return cudaGetLastError();
}

}  // namespace dentsph::gpu
