// Stepper: one way of stepping a State, behind one interface: the CPU step (the model's solver
// object, solver.hpp, which steps the host State in place), the CUDA backend and its CPU emulation
// (which keep the particles in their own memory between steps; backend.hpp). Every loop (the
// offline run, the haptic runtime, the viewer, replay) steps through a Simulation (simulation.hpp),
// which owns the host State and a Stepper.
//
// The host State is the one a caller reads and edits. After step() its small results (tool
// wrench, diagnostics, tool poses, time, step count, bond counters) are always current: the
// haptic path reads them every step for the price of a few bytes. Its particles are current only
// after sync_to_host() (a GPU downloads them; the CPU has nothing to do). An edit between steps
// (an increment, an instrument switch, a paste edit) changes the host State and hands it back with
// sync_from_host().
//
// Why no add_particles / remove_particles here: every edit the program makes reads the particles
// first (the free lattice sites of an increment, the height of the paste it drops on, which
// particles are the tool's), so the host must be current before the change whatever the backend;
// the edit is then sync_to_host, change, sync_from_host (Simulation::edit). A backend makes that
// cheap where it can: the CPU does nothing at either end, a GPU backend downloads at most once
// between two steps and takes a State of unchanged size back into the same memory without
// capturing its graphs again (a changed size costs new memory and a new capture).
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

class Stepper {
 public:
  virtual ~Stepper() = default;
  Stepper() = default;
  Stepper(const Stepper&) = delete;
  Stepper& operator=(const Stepper&) = delete;

  // The backend's name: "cpu", "cuda" or "cuda-emulation".
  virtual const char* name() const = 0;
  // What runs the step, for a person ("2 CPU threads", the GPU's name, "host emulation of the CUDA
  // backend").
  virtual std::string device_name() const = 0;

  // One step: the tool moves to `tool_pose` (also written to host.tool_pose). Afterwards host's
  // tool_wrench, diagnostics, tool_pose_applied, time, steps and bonds.counters are this step's.
  virtual void step(State& host, const Pose& tool_pose) = 0;
  // The same step with each stage's wall time added to `times` (slower on a GPU, which waits for
  // each stage; benchmarks).
  virtual void step_timed(State& host, const Pose& tool_pose, StageTimes& times) = 0;
  // Makes the whole of `host` current: particles (in the backend's order), bonds and the
  // per-particle results. Cheap when nothing was stepped since the last call.
  virtual void sync_to_host(State& host) = 0;
  // Takes `host` back as the state the next step starts from, after an edit between steps
  // (particles added, removed or changed). `host` must have been synced first.
  virtual void sync_from_host(const State& host) = 0;
  // Bytes its solver object keeps beyond the State (the CPU's: its buffers, solver.hpp; a GPU
  // backend's memory is its own: 0).
  virtual std::size_t solver_bytes() const { return 0; }
  // The wall time a step's solves may take from the step's start (0: no limit): past it they stop
  // and the step says so (StepOptions::deadline). The CPU's; a GPU step ignores it.
  virtual void set_solve_budget(double seconds) { (void)seconds; }
};

// How the CPU step's thread count is chosen: `threads` for every step, or up to `threads` by a
// ThreadGovernor (thread_governor.hpp) that times the steps and uses the fastest count (fewer when
// another program takes a core). Either gives the same result bit for bit.
enum class ThreadPolicy { fixed, governed };

// The CPU step of `model` on `threads` threads: the model's solver object (solver.hpp), sized for
// `state`, steps the host State itself. `model` is the caller's and must outlive the stepper, which
// reads it by reference at every step (a Simulation owns its run's Model).
std::unique_ptr<Stepper> make_cpu_stepper(const Model& model, const State& state, int threads,
                                          ThreadPolicy policy = ThreadPolicy::fixed);

}  // namespace dentsph
