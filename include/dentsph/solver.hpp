// A solver: one way of advancing a State by a step (docs/model.md, "Solvers"), as an object behind
// one interface, like SPlisHSPlasH's TimeStep classes; its stages are functions of
// (const Model&, State&), as MuJoCo's are of (mjModel, mjData). Each solver owns the buffers its step
// needs beyond the State (resize() sizes them, so that a step allocates nothing) and answers what
// the rest of the program asks of a solver: its name, its stability limits, the time step a dental
// scene takes with it, the layers of its instruments and its figures for summary.json. Nothing
// outside the solvers and their registry asks which solver it is.
//
// The solvers are listed in one place, the registry (src/solver/registry.cpp): adding one is a
// folder with its step and its StepSolver, a key in the Solver enum and one registration line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

// A run's figures of a solver's steps (summary.json's "solver"), added up step by step by
// StepSolver::record. A solver that records nothing (the paper's step) leaves `recorded` false, and
// the summary names the solver alone.
struct SolverStatistics {
  bool recorded = false;
  std::uint64_t steps = 0;  // steps recorded
  // The pressure solve: iterations per step, the mean compression of the paste it left
  // (StepDiagnostics::density_error) and its error (StepDiagnostics::pressure_residual).
  double iterations_sum = 0;
  int iterations_max = 0;
  double density_error_sum = 0, density_error_max = 0, pressure_residual_max = 0;
  // The compression measured at each step's start (StepDiagnostics::compression_mean, _max): the
  // mean over steps of its mean, the largest of its mean, and the largest of one particle's.
  double compression_sum = 0, compression_mean_max = 0, compression_max = 0;
  double viscous_pressure_max = 0;  // Pa, the largest viscous pressure (StepDiagnostics::viscous_pressure_max)
  // Steps whose pressure solve stopped on its budget (StepDiagnostics::pressure_on_budget), and the
  // largest error it stopped at.
  std::uint64_t on_budget_steps = 0;
  double on_budget_residual_max = 0;
  // Steps a solve of which stopped at the step's deadline (StepDiagnostics::on_deadline; realtime
  // runs), and the largest pressure error one stopped at.
  std::uint64_t on_deadline_steps = 0;
  double on_deadline_residual_max = 0;
  // The largest density error of a material particle a solve left (StepDiagnostics::pressure_max_error:
  // the cg solve's; 0 for Jacobi, which does not measure it).
  double pressure_max_error = 0;
  // The implicit viscosity: its iterations a step (sum, largest) and its relative residual (mean, largest).
  double viscosity_iterations_sum = 0;
  int viscosity_iterations_max = 0;
  double viscosity_residual_sum = 0, viscosity_residual_max = 0;
  // A non-Newtonian material's Picard iterations a step (sum, largest) and the range of its
  // effective viscosities over the run, Pa s (StepDiagnostics; all 0 without one).
  double rheology_iterations_sum = 0;
  int rheology_iterations_max = 0;
  double viscosity_min = 0, viscosity_max = 0;
  // Times the wall field moved a paste particle out of the walls (StepDiagnostics::wall_projections),
  // summed over the run, and in how many steps.
  std::uint64_t wall_projections = 0, wall_projection_steps = 0;
  // Steps taken in equal parts (a velocity limit under dt), and the most parts.
  std::uint64_t substepped_steps = 0;
  int substeps_max = 1;
  // Paste held at the domain's edge after the last step (StepDiagnostics::held,
  // Model::hold_outside_domain): it fell off the model.
  std::uint64_t held_outside_domain = 0;

  double iterations_mean() const { return steps > 0 ? iterations_sum / double(steps) : 0; }
  double density_error_mean() const { return steps > 0 ? density_error_sum / double(steps) : 0; }
  double compression_mean() const { return steps > 0 ? compression_sum / double(steps) : 0; }
  double viscosity_iterations_mean() const { return steps > 0 ? viscosity_iterations_sum / double(steps) : 0; }
  double rheology_iterations_mean() const { return steps > 0 ? rheology_iterations_sum / double(steps) : 0; }
  double viscosity_residual_mean() const { return steps > 0 ? viscosity_residual_sum / double(steps) : 0; }
};

class StepSolver {
 public:
  virtual ~StepSolver() = default;
  StepSolver() = default;
  StepSolver(const StepSolver&) = delete;
  StepSolver& operator=(const StepSolver&) = delete;

  // ---- who it is ----------------------------------------------------------------------------
  virtual Solver key() const = 0;  // its key in the registry (Model::solver)
  // Its name: scene files' simulation.solver, --solver, summary.json ("paper", "iisph").
  virtual const char* name() const = 0;
  // What it is, for a person ("the paper's explicit step").
  virtual const char* description() const = 0;

  // ---- stepping -----------------------------------------------------------------------------
  // Sizes its own buffers for `state` (after particles were added or removed, between steps), so
  // that step() allocates nothing. step() calls it itself when handed a State of another layout
  // (State::layout()), so a step is never taken on buffers of the wrong size.
  virtual void resize(const Model& model, const State& state) = 0;
  // One step of `model` on `state`: the tool moves to state.tool_pose.
  virtual void step(const Model& model, State& state, const StepOptions& options) = 0;
  // Bytes held by its buffers.
  virtual std::size_t bytes() const = 0;

  // ---- its time step ------------------------------------------------------------------------
  // The dental scenes' time step with it (s).
  virtual real default_time_step() const = 0;
  // Given the paper's acoustic and viscous limits of `l` (paper_acoustic, paper_viscous) and the
  // largest stiffness kp_max (m^2/s^2): the limits that bind it (acoustic, viscous) and the fastest
  // signal it carries (sound_speed).
  virtual void set_limits(const Model& model, real kp_max, StabilityLimits& l) const = 0;
  // The limit the last step's motion sets (StabilityLimits::force), infinite before any step, and
  // its name for messages ("force", "velocity CFL").
  virtual real motion_limit(const Model& model, const StepDiagnostics& diagnostics) const = 0;
  virtual const char* motion_limit_name() const = 0;
  // The largest dt a tool moving at `tool_speed` m/s allows (infinite where the tool's speed does not
  // limit it).
  virtual real tool_speed_limit(const Model& model, real tool_speed) const = 0;
  // Why model.dt is too large for it (a message naming the limit and the fixes), or "" when it is not.
  virtual std::string time_step_problem(const Model& model, const StabilityLimits& l, real tool_speed) const = 0;
  // Its time step and the limits on it, one line for a person (`dentsph validate`).
  virtual std::string time_step_report(const Model& model, const StabilityLimits& l, real tool_speed) const = 0;

  // ---- what the scene builds for it -----------------------------------------------------------
  // Particle layers of its instruments' shells (tools.hpp).
  virtual int instrument_layers() const = 0;
  // Whether it keeps material out of Model::walls (a dental scene builds the wall field for it).
  virtual bool uses_walls() const = 0;

  // ---- its figures over a run ---------------------------------------------------------------
  // Adds the step just taken (its diagnostics) to `stats`; nothing for a solver without figures.
  virtual void record(SolverStatistics& stats, const StepDiagnostics& diagnostics) const {
    (void)stats;
    (void)diagnostics;
  }
};

// ---- the registry (src/solver/registry.cpp) -------------------------------------------------
struct SolverEntry {
  Solver key;
  const char* name;
  std::unique_ptr<StepSolver> (*make)();
};
// Every solver, in the order they are offered ("paper" first: the scene files' default).
std::span<const SolverEntry> registered_solvers();
// A new solver object of `key` (its buffers empty until resize()).
std::unique_ptr<StepSolver> make_solver(Solver key);
// The registry's own object of `key`, for what a solver answers without stepping (never stepped).
const StepSolver& solver_properties(Solver key);

}  // namespace dentsph
