// Simulation: the one run core behind every loop. It owns the host State and a Stepper (any
// backend) for a Scene, and keeps the bookkeeping around a step that every loop needs: the
// procedure's events due, the tool's pose from the keyframes (or from a caller: a device, the
// mouse), edits between steps (increments, instrument switches, paste edits) through the stepper,
// the force limit, divergence with its one message, and the run's statistics. The loops are thin
// around it: the offline run (run.hpp), the haptic runtime's simulation loop (haptics.hpp), the
// viewer's session (apps/viewer) and replay (haptics/recording.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <optional>

#include "dentsph/active_lights.hpp"
#include "dentsph/backend.hpp"
#include "dentsph/cure.hpp"
#include "dentsph/force_stats.hpp"
#include "dentsph/dispense.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/solver.hpp"
#include "dentsph/step.hpp"
#include "dentsph/stepper.hpp"

namespace dentsph {

// The scene's dt is over a stability limit and the run was not forced. what() says by how much
// and how to fix it.
class UnstableTimeStep : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The limits of a scene's initial state, and an error (UnstableTimeStep) when dt exceeds one of
// them and `allow_unstable` is false: the limits the scene's solver names (StepSolver::time_step_problem:
// the paper's step's acoustic and viscous limits, the iisph solver's velocity CFL limit against the
// tool's fastest speed between its keyframes).
StabilityLimits check_time_step(const Scene& scene, const State& state, bool allow_unstable);

// How a run advances a long cure (Simulation::advance_cure_at_rest; docs/architecture.md,
// "Curing"): while the light is on and nothing else happens (no event due, the tool still in its
// keyframes, the paste at rest), the cure goes on in updates of `update` s of light each, and the
// paste is stepped `steps_between` steps after each (more, at dt, while it moves faster than
// `rest_speed`). The dose does not depend on the update's length (test_cure); the result agrees
// with a cure stepped at dt throughout (test_cure_physics, "CureAtRest").
struct CureSchedule {
  real update = 0.02;       // s of light per large update
  int steps_between = 10;   // steps of the paste after each large update
  real rest_speed = 5e-4;   // m/s: the paste is at rest while its fastest particle is slower
                            // (of those in the cavity's box grown by 4 h in dental scenes, in the
                            // domain otherwise: a particle flung away does not count)
};

// What a run did, as summary.json reports it (docs/outputs.md). The Simulation fills what it
// knows (Simulation::summary); each loop adds its own (wall time, snapshots, assessment, ...).
struct RunSummary {
  std::string scene, status = "completed";  // status: completed | diverged
  std::string paste_preset;                 // Scene::paste_preset (`run --material`); empty: the scene's own paste
  double paste_temperature_c = 23;          // Scene::paste_temperature_c
  std::string message;                      // why a run diverged
  std::string backend = "cpu";              // the stepper's: cpu | cuda | cuda-emulation
  std::uint64_t steps = 0;
  real sim_time_s = 0;
  double wall_time_s = 0;
  double steps_per_second = 0;
  std::uint32_t material = 0, boundary = 0, tool = 0;  // material: the paste, set by the cure or not
  std::uint64_t bonds_current = 0;
  BondCounters bonds;
  real dt = 0;
  StabilityLimits limits;          // acoustic and viscous from the scene; force: the smallest seen
  bool acoustic_violated = false, viscous_violated = false, forced = false;
  std::uint64_t force_violation_steps = 0;  // steps whose dt exceeded the force limit
  real first_force_violation_t = -1;        // s, -1 if none
  real peak_tool_force_N = 0;        // simulated N: the largest force on the tool in the simulation
  real force_scale = 1;              // device N per simulated N (Scene::force_scale)
  std::uint64_t snapshots = 0;
  std::uint64_t surfaces = 0;        // the paste's surfaces written beside them (paste_surface.pvd)
  double surface_seconds = 0;        // wall s spent building and writing those surfaces
  std::uint64_t events_applied = 0;  // procedure events (dispense, switch_tool) that took place
  std::string assessment_json;       // dental scenes: the filling's assessment (JSON object)
  std::string cavity_json;           // dental scenes: the cavity (JSON object, dental.hpp cavity_json())
  std::string assessment_report;     // dental scenes: the same, for a person
  std::string grading_report;        // dental scenes with an output folder: the surface graded, for a person
  int threads = 1;
  Solver solver = Solver::paper;     // the step that ran
  PressureSolve pressure_solve = PressureSolve::jacobi;  // its pressure solve (the iisph solver's)
  PressureGradient gradient = PressureGradient::spiky;   // its pressure's kernel gradient (iisph)
  DensityKernel density_kernel = DensityKernel::poly6;   // the kernel its density is summed with (iisph)
  double viscous_pressure = 0;  // its viscous pressure's step (iisph.viscous_pressure; 0: none)
  // Its figures over the run (solver.hpp; none recorded by the paper's step).
  SolverStatistics solver_statistics;
  // Curing (scenes with cure events or a curing light turned on): light-on time, how much of it
  // was advanced in large updates (CureSchedule) and in how many; the cure's assessment (JSON
  // object, cure_assessment_json; empty without curing) and its text.
  bool curing = false;
  real light_on_s = 0, cure_at_rest_s = 0;
  std::uint64_t cure_updates_at_rest = 0;
  std::string cure_json, cure_report;
  std::string realtime_json;         // realtime runs: a JSON object whose members ("haptic", "sim",
                                     // "consumer", "device") are added to summary.json
};

struct SimulationOptions {
  Backend backend = Backend::cpu;
  int threads = 1;              // threads of the CPU step (the most it uses, with the governor)
  bool allow_unstable = false;  // step even when dt is over the acoustic or viscous limit
  // governed: the CPU step uses the fastest count up to `threads`, timed as it runs (fewer when
  // another program takes a core); fixed: always `threads`. The results are the same bit for bit.
  ThreadPolicy thread_policy = ThreadPolicy::governed;
  CureSchedule cure_schedule = {};
  // The wall time (s) a step's solves may take from its start, 0 for none (StepOptions::deadline):
  // `run --realtime` gives a share of dt, so that a step stopped early keeps the haptic loop in
  // time; the summary counts such steps (solver.on_deadline). Offline runs leave it 0.
  double solve_budget_s = 0;
};

class Simulation {
 public:
  // The scene's initial state (make_state) and the stepper of `options.backend` for it. Throws
  // UnstableTimeStep when dt is over a limit (unless allowed) and CudaUnavailable where the cuda
  // backend cannot run. `scene` must outlive the Simulation. The run's Model starts as the scene's
  // and is the Simulation's alone: its stepper reads it by reference, set_paste edits it.
  Simulation(const Scene& scene, const SimulationOptions& options = {});
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const Scene& scene() const { return scene_; }
  const Model& model() const { return model_; }
  const Stepper& stepper() const { return *stepper_; }
  int threads() const { return options_.threads; }

  // The host State. Its small results (tool_wrench, diagnostics, tool_pose_applied, time, steps,
  // bonds.counters) are current after every step; its particles only after synced().
  const State& state() const { return state_; }
  // The whole State current (a GPU backend downloads, once at most between two steps).
  const State& synced();
  // The State to change between steps (particles added, removed or changed): synced here, handed
  // back to the stepper before the next step.
  State& edit();

  // The tool's pose from the scene's keyframes at the end of the next step.
  Pose keyframe_pose() const { return scene_.tool.at(state_.time + model_.dt); }
  // Applies the scene's procedure events due before the next step (those at t <= time + dt / 2,
  // so that an event at t lands on the step at t), in order, calling on_applied(index) after each.
  // Returns how many.
  std::size_t apply_due_events(const std::function<void(std::size_t)>& on_applied = {});
  // Applies the scene's event `index` now (a replay applies them at their recorded steps).
  void apply_event(std::size_t index);
  // An increment of `volume` m^3 of `paste` dropped on the tooth's axis (dispense_increment).
  // Returns the particles added.
  std::size_t dispense(real volume, const IncrementPaste& paste);
  // The instrument `name` in place of the tool (switch_instrument; std::invalid_argument for an
  // unknown name, nothing changed).
  void switch_instrument(const std::string& name);
  // An edit of the run's paste, made here on the Model this Simulation owns (its stepper reads
  // that one): the paste material's (MaterialTable::paste, or the entry of scene_paste's) viscosity,
  // stiffness and adhesion strength become `paste`'s (its rest density stays), so every particle of
  // it takes them (other materials, and paste the cure has changed, keep theirs), and the adhesion
  // kernel becomes `adhesion`'s (A, B, eps, zeta; its constants derived again). The rest of the
  // Model (dt, h, the grid, the wall field, the materials) stays the run's. Throws
  // std::invalid_argument naming the field for an impossible kernel, and UnstableTimeStep naming
  // the limit where dt would be over the acoustic or viscous limit of the State that gives; either
  // way nothing changes.
  void set_paste(const AdhesionParams& adhesion, const Material& paste);

  // One step with the tool moved to `tool_pose`: the statistics and the force limit updated,
  // divergence checked, and, when the run cures, the cure updated for the step
  // (cure_between_steps with the light on: a hand-held one, set_light, or the scene's cure event's).
  // A GPU backend downloads the particles only for a cure pass (every
  // CureModel::transition_interval while the light is on) and takes them back when it changed
  // them; the CPU cures its State in place. False once the simulation has diverged (the step was
  // taken; a loop stops).
  bool step(const Pose& tool_pose);

  // ---- curing (docs/architecture.md, "Curing") --------------------------------------------------
  // Whether the run cures: the scene has cure events, its paste sets by itself, or a light was turned
  // on (set_light).
  bool curing() const { return cure_.has_value(); }
  // The cure's model (nullptr while the run does not cure): the scene's paste, cured as its cure
  // preset (scene_paste_cure: "composite", or "amalgam", which sets by itself: such a run cures
  // from its start).
  const CureModel* cure_model() const { return cure_ ? &*cure_ : nullptr; }
  // A hand-held light (the viewer's key, the device's second button): on from now until turned off
  // (nullopt); it takes the place of the scene's cure events while on. The first light turned on
  // makes the run cure.
  void set_light(const std::optional<CuringLight>& light);
  const std::optional<CuringLight>& hand_light() const { return hand_light_; }
  // The hand-held light over the cavity (light_over_cavity) turned on when off, off when on: the
  // device's second button, recorded (kLightToggle) and replayed.
  void toggle_light() { set_light(hand_light_ ? std::nullopt : std::optional<CuringLight>(light_over_cavity())); }
  // The light on over the next step: the hand-held one, else the scene's event's at the step's
  // midpoint.
  std::optional<CuringLight> light() const;
  // The light over the cavity: its window 1 mm above the occlusal reference (or a spacing above the
  // highest paste in its beam, a heap above the cavity), pointing down the tooth's axis (dental scenes; otherwise a kernel radius above the paste's top, over its middle,
  // down -z, its window at least as wide as the paste).
  CuringLight light_over_cavity() const;
  // Advances the cure by one large update when the run can (CureSchedule): the scene's light is on
  // and stays so, no event is due and the tool stands still in its keyframes for the update, the
  // paste is at rest (its fastest particle where it is filled, paste_at_rest(), under rest_speed) and
  // steps_between steps were taken since the last update; the update ends by `until` (s) at the
  // latest. Returns the simulated time it advanced (0: nothing done, step instead).
  real advance_cure_at_rest(real until);
  // Whether the run is curing at rest: a large update was made within the last steps_between steps.
  bool curing_at_rest() const {
    return cure_updates_at_rest_ > 0 && steps_since_cure_update_ <= options_.cure_schedule.steps_between;
  }
  // What the last cure update did.
  const CureUpdate& last_cure() const { return last_cure_; }

  bool diverged() const { return diverged_; }
  // Why it diverged (what, when, and the fix); empty while it has not.
  const std::string& divergence() const { return divergence_; }
  // Acoustic, viscous and sound speed of the State (initial, or after set_paste); force: the
  // smallest force limit seen (infinite before any step).
  const StabilityLimits& limits() const { return limits_; }
  // The tool force after every step (peak, impulse, time in contact).
  const ForceStats& forces() const { return forces_; }
  std::uint64_t force_violation_steps() const { return force_violation_steps_; }
  std::uint64_t events_applied() const { return events_applied_; }

  // What the core knows of the run (scene, backend, threads, steps, time, particles, bonds,
  // stability, forces, events, status; the cavity of a dental scene; the cure's figures and, for a
  // dental scene that cures, its assessment), from the synced State.
  RunSummary summary();

 private:
  void rebuild_stepper();
  // The stepper of the options' backend for model_ and state_, with the options' solve budget.
  std::unique_ptr<Stepper> new_stepper() const;
  void start_curing();
  void cure_after_step(real t_before);
  // s: until when the tool stands still in the keyframes from `t` (t itself when it moves).
  real tool_still_until(real t) const;
  // Whether the paste is at rest: the fastest material particle of the last step under `speed`,
  // or else of those within the cavity's box grown by 4 h (dental scenes; within the domain for the
  // others), so that a particle flung away or falling off the instrument does not keep the cure
  // stepping at dt. (Those far particles then wait out the update where they are.)
  bool paste_at_rest(real speed);

  const Scene& scene_;
  SimulationOptions options_;
  Model model_;
  State state_;
  std::unique_ptr<Stepper> stepper_;
  bool edited_ = false;  // the host State changed since the stepper last took it
  std::size_t next_event_ = 0;
  StabilityLimits limits_;
  bool acoustic_violated_ = false, viscous_violated_ = false;
  ForceStats forces_;
  std::uint64_t force_violation_steps_ = 0;
  real first_force_violation_t_ = -1;
  std::uint64_t events_applied_ = 0;
  // The model's solver (the registry's object: its limits and figures) and its figures over the
  // steps taken (StepSolver::record).
  const StepSolver& solver_;
  SolverStatistics solver_statistics_;
  bool diverged_ = false;
  std::string divergence_;
  // Curing.
  std::optional<CureModel> cure_;
  ActiveLights lights_;
  std::optional<CuringLight> hand_light_;
  CureUpdate last_cure_;
  int steps_since_cure_update_ = 0;
  real light_on_s_ = 0, cure_at_rest_s_ = 0;
  std::uint64_t cure_updates_at_rest_ = 0;
};

}  // namespace dentsph
