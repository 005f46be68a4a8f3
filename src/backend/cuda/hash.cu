// Stage 1 on the device: each particle's sort bucket.
#include "backend/cuda/hash.hpp"
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"

namespace dentsph::gpu {

__global__ void hash_kernel(StepView v) {
  const std::uint32_t i = thread_index();
  if (i < v.n) hash_body(v, i);
}

cudaError_t launch_hash(const StepView& v, cudaStream_t s) {
  hash_kernel<<<grid_for(v.n), kBlock, 0, s>>>(v);
  return cudaGetLastError();
}

}  // namespace dentsph::gpu
