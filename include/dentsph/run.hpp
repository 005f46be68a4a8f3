// Offline runs: step a scene for a number of steps, writing particle snapshots, the tool force
// per step and a summary (docs/outputs.md). The same loop the command `dentsph run` uses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

#include "dentsph/backend.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

// The scene's dt is over a stability limit and the run was not forced. what() says by how much
// and how to fix it.
class UnstableTimeStep : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunProgress {
  std::uint64_t step = 0, total = 0;
  real sim_time = 0;  // s
  double wall_s = 0;  // s since the run started
  double eta_s = 0;   // s, estimated wall time left
};

struct RunOptions {
  std::uint64_t steps = 0;          // steps to take; 0: from `duration`
  real duration = 0;                // s of simulated time when steps == 0 (0: the scene's run.duration)
  std::filesystem::path out_dir;    // where to write; empty: write nothing
  bool allow_unstable = false;      // run even when dt is over the acoustic or viscous limit
  int threads = 1;                  // threads of the parallel stages
  Backend backend = Backend::cpu;   // cuda: the particles stay on the GPU, downloaded for outputs
  std::function<void(const RunProgress&)> on_progress;  // called about every 1% of the run
};

struct RunSummary {
  std::string scene, status = "completed";  // status: completed | diverged
  std::string message;                      // why a run diverged
  std::uint64_t steps = 0;
  real sim_time_s = 0;
  double wall_time_s = 0;
  double steps_per_second = 0;
  std::uint32_t material = 0, boundary = 0, tool = 0;
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
  std::uint64_t events_applied = 0;  // procedure events (dispense, switch_tool) that took place
  std::string assessment_json;       // dental scenes: the filling's assessment (JSON object)
  std::string cavity_json;           // dental scenes: the cavity (JSON object, dental.hpp cavity_json())
  std::string assessment_report;     // dental scenes: the same, for a person
  int threads = 1;
  Solver solver = Solver::paper;     // the step that ran
  // The iisph solver's pressure solve over the run: iterations per step and the mean compression
  // of the paste it left (StepDiagnostics::density_error), mean and largest; the solve's largest
  // error (StepDiagnostics::pressure_residual).
  double iterations_mean = 0;
  int iterations_max = 0;
  double density_error_mean = 0, density_error_max = 0, pressure_residual_max = 0;
  std::string realtime_json;         // realtime runs: a JSON object whose members ("haptic", "sim",
                                     // "consumer", "device") are added to summary.json
};

// The acoustic and viscous limits of a scene's initial state, and an error (UnstableTimeStep)
// when dt exceeds one of them and `allow_unstable` is false.
StabilityLimits check_time_step(const Scene& scene, const State& state, bool allow_unstable);

// Runs `scene` from its initial state. Throws UnstableTimeStep before stepping if dt is over a
// limit (unless allowed); a run whose material becomes non-finite stops and reports "diverged".
RunSummary run_offline(const Scene& scene, const RunOptions& options);

}  // namespace dentsph
