// Offline runs: step a scene for a number of steps, writing particle snapshots, the tool force
// per step and a summary (docs/outputs.md). The same loop the command `dentsph run` uses, a thin
// one around a Simulation (simulation.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "dentsph/backend.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

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

// Runs `scene` from its initial state. Throws UnstableTimeStep before stepping if dt is over a
// limit (unless allowed); a run whose material becomes non-finite stops and reports "diverged".
RunSummary run_offline(const Scene& scene, const RunOptions& options);

}  // namespace dentsph
