// One simulation step of the model's solver (solver.hpp): the paper's six stages (docs/model.md,
// "One step") or the iisph solver's ("Solvers"); the all-pairs reference; the time-step limits.
#pragma once

#include <limits>

#include <chrono>
#include <cstdint>
#include <string>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

// Wall time of each stage, summed over the steps that were given this struct (microseconds).
// The paper's step: pressure_us is measured by the GPU backend alone (the CPU step computes each
// particle's pressure inside its density pass, whose time is density_us), viscosity_us is 0. The
// iisph solver: density_us is its pair pass, forces_us the adhesion and gravity, pressure_us the
// pressure solve, viscosity_us the implicit viscosity, integrate_us the end of the step with the
// tool wrench (wrench_us 0).
struct StageTimes {
  double hash_us = 0, sort_us = 0, reorder_us = 0, density_us = 0, pressure_us = 0, forces_us = 0,
         wrench_us = 0, integrate_us = 0, viscosity_us = 0;
  std::uint64_t steps = 0;
  double total_us() const {
    return hash_us + sort_us + reorder_us + density_us + pressure_us + forces_us + wrench_us + integrate_us +
           viscosity_us;
  }
};

// How a step runs, not what it computes: every thread count gives the same result, bit for bit
// (each particle's sums are taken in the same order whichever thread takes them).
struct StepOptions {
  int threads = 1;              // threads for the parallel stages (OpenMP); 1 runs serially
  StageTimes* times = nullptr;  // when set, each stage's wall time is added to it
  // The iisph solver's solves stop iterating once this time has passed (after their least
  // iterations), and the step says so (StepDiagnostics::on_deadline): the haptic loop's share of
  // real time (SimulationOptions::solve_budget_s). The default never comes. A deadline makes the
  // result depend on the machine's speed; offline runs leave it unset.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
};

// One step of the model's solver (model.solver; solver.hpp): for the paper's, the grid step: cell
// keys, counting radix sort, reorder and cell ranges, density, pressure, forces over the 27
// neighbouring cells with the bond hysteresis of each moving particle, semi-implicit Euler; then the
// tool wrench. The tool moves to state.tool_pose. It steps with a solver object this thread keeps,
// which sizes its buffers for each State it is handed: allocation-free from the second step of a
// State on, until particles are added or removed. A loop holds a solver object of its own (a
// Stepper's, solver.hpp).
void step(const Model& model, State& state, const StepOptions& options = {});

// The all-pairs reference step (the paper's "less efficient algorithm"): the same physics with
// every pair visited, no grid and no reordering. Every faster path is tested against it.
void step_all_pairs(const Model& model, State& state);

// Mean number of neighbours within h per particle (self excluded), over the 27-cell grid.
real mean_neighbours(const Model& model, State& state);

// Time-step limits (docs/model.md, "Stability" and "Solvers"), in seconds. Which hold
// depends on the model's solver (StepSolver::set_limits): the paper's explicit step has its acoustic, viscous and force
// limits; the iisph solver treats pressure, viscosity and adhesion so that none of those binds, and
// is limited by the velocity CFL condition dt <= cfl h / max|v| alone.
struct StabilityLimits {
  real acoustic = 0;  // paper: lambda h / sqrt(max Kp); iisph: infinite
  real viscous = 0;   // paper: 0.125 h^2 min(rho0 / mu); iisph: infinite
  real force = 0;     // the limit the last step's motion sets (infinite before any step): paper
                      // 0.25 sqrt(h / max|a|); iisph the velocity CFL cfl h / max|v|
  real sound_speed = 0;  // m/s, the fastest signal the step carries: paper sqrt(max Kp), iisph h / dt;
                         // material moving at many times it has exploded
  // The paper's acoustic and viscous limits whatever the solver, for comparison (iisph: what its
  // dt is above).
  real paper_acoustic = 0, paper_viscous = 0;
  // With the iisph solver's surface tension sigma: its explicit forces' limit, the larger of the
  // capillary wave's sqrt(rho0 h^3 / (2 pi sigma)) (Brackbill et al. 1992) and the viscous damping's
  // mu h / sigma (an overdamped surface; min rho0 and mu of the material); infinite without.
  real capillary = std::numeric_limits<real>::infinity();
};
// With `paste`: the limits the State would have if the particles of the Model's paste material
// (model.materials.paste; without one, every material particle) were of that material (a paste
// edit checked before it is made).
StabilityLimits stability_limits(const Model& model, const State& state, const Material* paste = nullptr);
// The limit the last step's motion sets (StabilityLimits::force): the paper's force limit
// 0.25 sqrt(h / max|a|), or for the iisph solver the velocity CFL limit cfl h / max|v|; infinite
// before any step.
real force_time_step_limit(const Model& model, const StepDiagnostics& diagnostics);
// "simulation.dt: ... s is over the acoustic (...) stability limit of ... s (acoustic ..., viscous
// ...)" when `dt` is over the acoustic or viscous limit of `l`; empty otherwise.
std::string time_step_excess(real dt, const StabilityLimits& l);
// The velocity CFL limit cfl h / speed for a speed in m/s (infinite for 0).
real velocity_time_step_limit(const Model& model, real speed);
// Weakly compressible SPH keeps material far slower than its sound speed: material at
// `explosion_speed_factor` times it, or non-finite, has exploded (the offline run, the haptic
// runtime and the viewer stop on it).
inline constexpr real explosion_speed_factor = 10;
// A tool force no paste can exert, non-finite or over a meganewton (the built-in procedure's is a
// few newtons; a device renders at most tens), has exploded too: a solve that diverged under the
// tool gives one while the material still moves slowly.
inline constexpr real exploded_tool_force = 1e6;  // N
inline bool tool_force_exploded(const ToolWrench& w) { return !(norm(w.force) <= exploded_tool_force); }
inline bool exploded(const StepDiagnostics& d, const ToolWrench& w, real sound_speed) {
  return d.non_finite > 0 || d.max_speed > explosion_speed_factor * sound_speed || tool_force_exploded(w);
}

}  // namespace dentsph
