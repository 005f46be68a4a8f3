// Stage 3 on the device: densities (and, once after an upload, the static boundary part).
#include "backend/cuda/density.hpp"
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"

namespace dentsph::gpu {

__global__ void static_density_kernel(StepView v) {
  const std::uint32_t i = thread_index();
  if (i < v.n) static_density_body(v, i);
}

__global__ void density_kernel(StepView v) {
  const std::uint32_t i = thread_index();
  if (i < v.n) density_body(v, i);
}

cudaError_t launch_static_density(const StepView& v, cudaStream_t s) {
  static_density_kernel<<<neighbour_grid_for(v), v.neighbour_block, 0, s>>>(v);
  return cudaGetLastError();
}

cudaError_t launch_density(const StepView& v, cudaStream_t s) {
  density_kernel<<<neighbour_grid_for(v), v.neighbour_block, 0, s>>>(v);
  return cudaGetLastError();
}

}  // namespace dentsph::gpu
