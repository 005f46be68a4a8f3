// The iisph solver's step (solver/iisph.hpp lists its stages). The grid part is the paper's step's:
// cell keys, sort and reorder when the neighbour lists must be rebuilt (src/step).
#include <algorithm>
#include <cmath>

#include "solver/iisph.hpp"
#include "step/stage_clock.hpp"
#include "step/stages.hpp"

namespace dentsph::iisph {

namespace {

void one_step(const Model& model, State& state, IisphScratch& x, const StepOptions& opt) {
  const int t = opt.threads < 1 ? 1 : opt.threads;
  stages::StageClock clock(opt.times);
  const bool rebuild = stages::lists_need_rebuild(model, state, t, /*tool_listed=*/false);  // tool_pairs.cpp
  if (rebuild) {
    stages::compute_cell_keys(model, state, t);
    clock.lap(&StageTimes::hash_us);
    stages::sort_by_cell(model, state);
    clock.lap(&StageTimes::sort_us);
    stages::reorder(model, state, t, /*keep_pressure=*/true);  // the next solve starts from it
    stages::remember_build_positions(state, t);
    list_material(state, x);
    clock.lap(&StageTimes::reorder_us);
  } else {
    clock.lap(&StageTimes::reorder_us);
  }
  prepare_particles(model, state, x, t);
  compute_pairs(model, state, x, t, rebuild);  // density, pair rows, bonds formed below A
  list_active_rows(state, x);
  clock.lap(&StageTimes::density_us);
  advect(model, state, x, t);                  // bonds broken past B, adhesion, gravity: v*
  surface_tension(model, state, x, t);         // cohesion, curvature, wetting of walls: into v*
  clock.lap(&StageTimes::forces_us);
  state.diagnostics.on_deadline = false;
  solve_pressure(model, state, x, t, opt.deadline);  // the pressure; v* + dt a_p
  clock.lap(&StageTimes::pressure_us);
  const bool viscous_pressure = model.iisph.viscous_pressure > 0;
  if (viscous_pressure) push_viscous_pressure(model, state, x, t);  // + dt a_pv
  implicit_viscosity(model, state, x, t, opt.deadline);  // v**
  if (viscous_pressure) update_viscous_pressure(model, state, x, t);
  clock.lap(&StageTimes::viscosity_us);
  finish(model, state, x, t);                  // velocity, position, tool, diagnostics, wrench
  clock.lap(&StageTimes::integrate_us);
  state.diagnostics.rebuilt = rebuild;
}

}  // namespace

int substeps(const Model& model, const State& state) {
  const real v = state.diagnostics.max_speed;
  if (!(v > 0) || !std::isfinite(v)) return 1;
  const real n = std::ceil(model.dt / velocity_time_step_limit(model, v));
  return int(std::clamp<real>(n, 1, kMaxSubsteps));
}

void step(const Model& model, State& state, IisphScratch& x, const StepOptions& opt) {
  const int n = substeps(model, state);
  if (n == 1) {
    one_step(model, state, x, opt);
    state.diagnostics.substeps = 1;
    return;
  }
  // The last step's fastest paste would cross more than cfl h in dt: n equal steps, the tool
  // moved a share of the way in each, its wrench their mean, counted as one step (a run's steps
  // and recordings go by dt).
  // The model at dt / n, kept per thread: assigning into it reuses its tables' storage, so only the
  // first split step of a thread allocates.
  thread_local Model sub;
  sub = model;
  sub.dt = model.dt / n;
  const Pose from = state.tool_pose_applied, to = state.tool_pose;
  const std::uint64_t steps = state.steps;
  const real time = state.time;
  ToolWrench mean;
  std::uint64_t projections = 0;
  bool on_deadline = false;  // any part's solves cut short
  for (int k = 1; k <= n; ++k) {
    state.tool_pose = k == n ? to : interpolate(from, to, real(k) / real(n));
    one_step(sub, state, x, opt);
    mean.force += state.tool_wrench.force / real(n);
    mean.torque += state.tool_wrench.torque / real(n);
    projections += state.diagnostics.wall_projections;
    on_deadline = on_deadline || state.diagnostics.on_deadline;
  }
  state.tool_wrench = mean;
  state.steps = steps + 1;
  state.time = time + model.dt;
  state.diagnostics.wall_projections = projections;
  state.diagnostics.on_deadline = on_deadline;
  state.diagnostics.substeps = n;
}

}  // namespace dentsph::iisph
