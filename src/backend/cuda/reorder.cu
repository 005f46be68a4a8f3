// Stage 2b on the device: gather the particles into cell order.
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"
#include "backend/cuda/reorder.hpp"

namespace dentsph::gpu {

cudaError_t launch_reorder(const StepView& v, cudaStream_t s) { return launch_each<reorder_body>(v, kBlock, s); }

}  // namespace dentsph::gpu
