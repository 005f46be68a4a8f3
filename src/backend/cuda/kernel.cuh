// What every kernel of the CUDA backend shares: the index of the thread's particle, the launch
// shape, and the block sum of the reductions.
#pragma once

#include <cuda_runtime_api.h>

#include "backend/cuda/view.hpp"

namespace dentsph::gpu {

__device__ inline std::uint32_t thread_index() { return blockIdx.x * blockDim.x + threadIdx.x; }

inline unsigned grid_for(std::uint32_t n) { return blocks_for(n) > 0 ? blocks_for(n) : 1; }


// The kernel of a per-particle stage: body(v, i) for each particle i, a thread each.
template <void (*Body)(const StepView&, std::uint32_t)>
__global__ void each_particle(StepView v) {
  const std::uint32_t i = thread_index();
  if (i < v.n) Body(v, i);
}

// Launches each_particle<Body> in blocks of `block` threads on stream s.
template <void (*Body)(const StepView&, std::uint32_t)>
cudaError_t launch_each(const StepView& v, unsigned block, cudaStream_t s) {
  each_particle<Body><<<v.n > 0 ? (v.n + block - 1) / block : 1, block, 0, s>>>(v);
  return cudaGetLastError();
}

// Sums `mine` over the block (kBlock threads) and stores the sum in out[blockIdx.x]. A tree in
// shared memory: a fixed order, so the result is the same every run.
__device__ inline void block_sum(const StepSums& mine, StepSums* out) {
  __shared__ alignas(StepSums) unsigned char raw[sizeof(StepSums) * kBlock];
  StepSums* sh = reinterpret_cast<StepSums*>(raw);
  const unsigned t = threadIdx.x;
  sh[t] = mine;
  __syncthreads();
  for (unsigned stride = kBlock / 2; stride > 0; stride >>= 1) {
    if (t < stride) sh[t].add(sh[t + stride]);
    __syncthreads();
  }
  if (t == 0) out[blockIdx.x] = sh[0];
}

}  // namespace dentsph::gpu
