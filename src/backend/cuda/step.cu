// One step on the device, in the paper's order (the CPU's paper_step.cpp): keys, sort and cell ranges,
// reorder, density, pressure, forces and bonds, tool wrench, integration and the step's output.
// Enqueued once per direction into a CUDA graph (cuda_stepper.cpp), or stage by stage with events
// between the stages for their times.
#include "backend/cuda/launch.hpp"

namespace dentsph::gpu {

cudaError_t enqueue_step(const StepView& v, const SortScratch& scratch, cudaStream_t s, cudaEvent_t* marks) {
  int stage = 0;
  auto mark = [&]() -> cudaError_t { return marks ? cudaEventRecord(marks[stage++], s) : cudaSuccess; };
  cudaError_t e;
#define DENTSPH_ENQUEUE(call)                  \
  if ((e = (call)) != cudaSuccess) return e;   \
  if ((e = mark()) != cudaSuccess) return e
  if ((e = mark()) != cudaSuccess) return e;
  DENTSPH_ENQUEUE(launch_hash(v, s));            // 1. broad phase
  DENTSPH_ENQUEUE(launch_sort(v, scratch, s));   // 2. sort, cell ranges
  DENTSPH_ENQUEUE(launch_reorder(v, s));         //    and reorder
  DENTSPH_ENQUEUE(launch_density(v, s));         // 3. density
  DENTSPH_ENQUEUE(launch_pressure(v, s));        // 4. pressure
  DENTSPH_ENQUEUE(launch_forces(v, s));          // 5. forces, bond hysteresis
  DENTSPH_ENQUEUE(launch_tool_wrench(v, s));     //    force and torque on the tool
  if ((e = launch_integrate(v, s)) != cudaSuccess) return e;  // 6. integration
  if ((e = launch_finish(v, s)) != cudaSuccess) return e;     //    and the step's output
  return mark();
#undef DENTSPH_ENQUEUE
}

}  // namespace dentsph::gpu
