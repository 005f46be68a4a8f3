// What every kernel of the CUDA backend shares: the index of the thread's particle, the launch
// shape, and the block sum of the reductions.
#pragma once

#include "backend/cuda/view.hpp"

namespace dentsph::gpu {

__device__ inline std::uint32_t thread_index() { return blockIdx.x * blockDim.x + threadIdx.x; }

inline unsigned grid_for(std::uint32_t n) { return blocks_for(n) > 0 ? blocks_for(n) : 1; }

// The neighbour passes (density, forces) use smaller blocks than the rest (StepView::
// neighbour_block, 64 unless DENTSPH_CUDA_NEIGHBOUR_BLOCK says otherwise): a haptic scene of a few
// thousand particles then spreads over more of the GPU's 132 multiprocessors (kBlock threads a
// block would leave most of them idle). A tuning choice, not a correctness one (docs/cuda.md).
inline unsigned neighbour_grid_for(const StepView& v) {
  return v.n > 0 ? (v.n + v.neighbour_block - 1) / v.neighbour_block : 1;
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
