// Stage 1 on the GPU, per particle: its sort bucket (step/grid.hpp's bucket_of, the CPU's key).
#pragma once

#include "backend/cuda/view.hpp"
#include "step/grid.hpp"

namespace dentsph::gpu {

DENTSPH_HD inline void hash_body(const StepView& v, std::uint32_t i) {
  v.key[i] = grid::bucket_of(v.src.pos[i], v.src.role[i], v.grid);
}

}  // namespace dentsph::gpu
