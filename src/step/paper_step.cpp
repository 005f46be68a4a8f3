// The paper's grid step, in the paper's order (section 3.2).
#include "step/paper.hpp"
#include "step/stage_clock.hpp"
#include "step/stages.hpp"

namespace dentsph::paper {

void step(const Model& model, State& state, const StepOptions& opt) {
  const int t = opt.threads < 1 ? 1 : opt.threads;
  stages::StageClock clock(opt.times);
  // The broad phase, the sort and the reorder run when the neighbour lists must be rebuilt: every
  // step without a skin, else once some particle has moved half the skin (neighbour_lists.cpp).
  const bool rebuild = stages::lists_need_rebuild(model, state, t);
  if (rebuild) {
    stages::compute_cell_keys(model, state, t);    // 1. broad phase
    clock.lap(&StageTimes::hash_us);
    stages::sort_by_cell(model, state);            // 2. sort, cell ranges
    clock.lap(&StageTimes::sort_us);
    stages::reorder(model, state, t);                     //    and reorder
    stages::remember_build_positions(state, t);
    clock.lap(&StageTimes::reorder_us);
  } else {
    clock.lap(&StageTimes::reorder_us);
  }
  // 3. density (and the lists on a rebuild), and 4. each particle's pressure in the same pass
  // (its time is in density_us; pressure_us is the GPU's, where it is a kernel of its own).
  stages::compute_density(model, state, t, rebuild);
  clock.lap(&StageTimes::density_us);
  stages::compute_forces(model, state, t);         // 5. forces, and bond hysteresis of moving particles
  clock.lap(&StageTimes::forces_us);
  stages::compute_tool_wrench(state);              //    force and torque on the tool
  clock.lap(&StageTimes::wrench_us);
  stages::integrate(model, state, t);              // 6. integration
  clock.lap(&StageTimes::integrate_us);
  state.diagnostics.rebuilt = rebuild;
}

}  // namespace dentsph::paper
