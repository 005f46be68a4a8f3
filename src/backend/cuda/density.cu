// Stage 3 on the device: densities (and, once after an upload, the static boundary part). The
// neighbour passes run in blocks of v.neighbour_block threads (docs/cuda.md, "Launch shapes").
#include "backend/cuda/density.hpp"
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"

namespace dentsph::gpu {

cudaError_t launch_static_density(const StepView& v, cudaStream_t s) {
  return launch_each<static_density_body>(v, v.neighbour_block, s);
}

cudaError_t launch_density(const StepView& v, cudaStream_t s) {
  return launch_each<density_body>(v, v.neighbour_block, s);
}

}  // namespace dentsph::gpu
