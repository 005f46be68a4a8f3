// The iisph solver's step (solver/iisph.hpp lists its stages). The grid part is the paper's step's:
// cell keys, sort and reorder when the neighbour lists must be rebuilt (src/step).
#include "solver/iisph.hpp"
#include "step/stage_clock.hpp"
#include "step/stages.hpp"

namespace dentsph::iisph {

void step(const Model& model, State& state, const StepOptions& opt) {
  const int t = opt.threads < 1 ? 1 : opt.threads;
  stages::StageClock clock(opt.times);
  const bool rebuild = stages::lists_need_rebuild(model, state, t, /*tool_listed=*/false);  // tool_pairs.cpp
  if (rebuild) {
    stages::compute_cell_keys(model, state, t);
    clock.lap(&StageTimes::hash_us);
    stages::sort_by_cell(model, state);
    clock.lap(&StageTimes::sort_us);
    stages::reorder(model, state, t);
    stages::remember_build_positions(state, t);
    list_material(state);
    clock.lap(&StageTimes::reorder_us);
  } else {
    clock.lap(&StageTimes::reorder_us);
  }
  prepare_particles(model, state, t);
  compute_pairs(model, state, t, rebuild);   // density, pair rows, bonds formed below A
  list_active_rows(state);
  clock.lap(&StageTimes::density_us);
  advect(model, state, t);                   // bonds broken past B, adhesion, gravity: v*
  clock.lap(&StageTimes::forces_us);
  solve_pressure(model, state, t);           // the pressure; v* + dt a_p
  clock.lap(&StageTimes::pressure_us);
  implicit_viscosity(model, state, t);       // v**
  clock.lap(&StageTimes::viscosity_us);
  finish(model, state, t);                   // velocity, position, tool, diagnostics, wrench
  clock.lap(&StageTimes::integrate_us);
  state.diagnostics.rebuilt = rebuild;
}

}  // namespace dentsph::iisph
