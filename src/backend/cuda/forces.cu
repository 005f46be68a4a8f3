// Stage 5 on the device: force densities and bond hysteresis, a thread per particle (each changes
// only its own bond list); the rare bond events are added to the step's counters atomically.
#include "backend/cuda/forces.hpp"
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"

namespace dentsph::gpu {

__global__ void forces_kernel(StepView v) {
  const std::uint32_t i = thread_index();
  if (i >= v.n) return;
  BondEvents ev;
  forces_body(v, i, ev);
  if (ev.formed) atomicAdd(&v.events->formed, ev.formed);
  if (ev.broken) atomicAdd(&v.events->broken, ev.broken);
  if (ev.overflowed) atomicAdd(&v.events->overflowed, ev.overflowed);
}

cudaError_t launch_forces(const StepView& v, cudaStream_t s) {
  forces_kernel<<<(v.n + v.neighbour_block - 1) / v.neighbour_block, v.neighbour_block, 0, s>>>(v);
  return cudaGetLastError();
}

}  // namespace dentsph::gpu
