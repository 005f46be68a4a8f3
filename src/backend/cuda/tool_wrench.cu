// The tool wrench on the device: per-block sums of each tool particle's force and moment (before
// integration moves the particles), into partials [0, blocks).
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"
#include "backend/cuda/tool_wrench.hpp"

namespace dentsph::gpu {

__global__ void tool_wrench_kernel(StepView v) {
  const std::uint32_t i = thread_index();
  block_sum(i < v.n ? wrench_term(v, i) : StepSums{}, v.partials);
}

cudaError_t launch_tool_wrench(const StepView& v, cudaStream_t s) {
  tool_wrench_kernel<<<grid_for(v.n), kBlock, 0, s>>>(v);
  return cudaGetLastError();
}

}  // namespace dentsph::gpu
