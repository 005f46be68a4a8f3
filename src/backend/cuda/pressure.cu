// Stage 4 on the device: pressure and volume.
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"
#include "backend/cuda/pressure.hpp"

namespace dentsph::gpu {

__global__ void pressure_kernel(StepView v) {
  const std::uint32_t i = thread_index();
  if (i < v.n) pressure_body(v, i);
}

cudaError_t launch_pressure(const StepView& v, cudaStream_t s) {
  pressure_kernel<<<grid_for(v.n), kBlock, 0, s>>>(v);
  return cudaGetLastError();
}

}  // namespace dentsph::gpu
