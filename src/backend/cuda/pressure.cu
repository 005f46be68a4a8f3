// Stage 4 on the device: pressure and volume.
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"
#include "backend/cuda/pressure.hpp"

namespace dentsph::gpu {

cudaError_t launch_pressure(const StepView& v, cudaStream_t s) { return launch_each<pressure_body>(v, kBlock, s); }

}  // namespace dentsph::gpu
