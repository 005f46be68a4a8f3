// Stage 2b on the device: gather the particles into cell order.
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"
#include "backend/cuda/reorder.hpp"

namespace dentsph::gpu {

__global__ void reorder_kernel(StepView v) {
  const std::uint32_t k = thread_index();
  if (k < v.n) reorder_body(v, k);
}

cudaError_t launch_reorder(const StepView& v, cudaStream_t s) {
  reorder_kernel<<<grid_for(v.n), kBlock, 0, s>>>(v);
  return cudaGetLastError();
}

}  // namespace dentsph::gpu
