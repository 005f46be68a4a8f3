// The step's reductions on the GPU: per-block partial sums (kBlock particles each; the tool wrench
// in partials [0, blocks), the integration diagnostics in [blocks, 2 blocks)), then one pass that
// adds the partials in order and writes the step's output.
#pragma once

#include "backend/cuda/view.hpp"

namespace dentsph::gpu {

// The output of a step from its partial sums (run by one thread).
DENTSPH_HD inline void finish_body(const StepView& v) {
  StepSums total;
  for (std::uint32_t b = 0; b < v.partial_count; ++b) total.add(v.partials[b]);
  v.out->sums = total;
  v.out->events = *v.events;
}

}  // namespace dentsph::gpu
