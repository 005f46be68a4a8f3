// The CUDA backend's entry points in a build without CUDA (DENTSPH_CUDA=OFF, or no nvcc found
// when configuring): they say so.
#include "backend/cuda/engine.hpp"
#include "dentsph/backend.hpp"

namespace dentsph {

namespace {
constexpr const char* kReason =
    "this build has no CUDA backend: it was configured without nvcc (reconfigure with -DDENTSPH_CUDA=ON and "
    "CMAKE_CUDA_COMPILER=/usr/local/cuda/bin/nvcc, or use the cuda preset)";
}

bool cuda_built() { return false; }

CudaStatus cuda_status() { return {false, kReason, ""}; }

std::unique_ptr<gpu::Engine> gpu::make_cuda_engine(const Model&, const State&) { throw CudaUnavailable(kReason); }

}  // namespace dentsph
