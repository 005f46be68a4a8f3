// Stage 1 on the device: each particle's sort bucket.
#include "backend/cuda/hash.hpp"
#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"

namespace dentsph::gpu {

cudaError_t launch_hash(const StepView& v, cudaStream_t s) { return launch_each<hash_body>(v, kBlock, s); }

}  // namespace dentsph::gpu
