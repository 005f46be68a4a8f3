// The simulation loop: a thin loop around a Simulation (the State, its stepper and the run's
// bookkeeping). Takes the newest tool command, applies the procedure's events at their simulated
// time (and an increment of paste on each press of the device's button 1), steps, publishes the
// tool force (scaled to device newtons) and, at the snapshot rate, the particle positions. Paced
// to real time (never ahead of the wall clock) or free-running; optionally capped at a step rate
// (a slow simulation).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "dentsph/contact.hpp"
#include "dentsph/haptics.hpp"
#include "dentsph/simulation.hpp"
#include "haptics/shared.hpp"
#include "haptics/timing_stats.hpp"

namespace dentsph::haptics {

// Steps between published outputs: 1, or, for a step longer than a haptic tick that is not a whole
// number of ticks, the fewest steps (at most 8) that are (1.5 ms at 1 kHz: 2, every 3 ms). Outputs
// of every 1.5 ms step reach a 1 kHz loop 1 and 2 ticks apart in turn, and the rendered coupling
// force carries that beat: on the press scene it gave the hand back 1.6 to 2.7% of its work (the
// passivity test allows 1%), published every second step nothing (docs/haptics.md).
int publish_every(double dt_s, double haptic_rate_hz);

class SimLoop {
 public:
  // `band`: the scene's matrix band (scene_rigid_band), rigid with the set paste.
  SimLoop(Simulation& sim, const RealtimeOptions& options, double force_scale, RuntimeShared& shared,
          std::vector<Vec3> band = {});
  // Runs on the calling thread from t0_ns until shared.stop is set or should_stop(now) says so
  // (then it sets shared.stop), or the simulation diverges.
  void run(std::int64_t t0_ns, const std::function<bool(std::int64_t)>& should_stop);
  SimReport report() const;

  std::vector<StepSample> steps;    // every step's tool pose and force
  std::vector<EventSample> events;  // the procedure events applied

 private:
  void publish_snapshot(std::int64_t now_ns);
  // Sends the contact loop what is rigid and the instrument when they changed (RigidWatch; checked
  // every kRigidCheckNs of wall time).
  void publish_rigid(std::int64_t now_ns);

  Simulation& sim_;
  RealtimeOptions opt_;
  double force_scale_;
  RuntimeShared& shared_;
  DurationHistogram step_times_;
  SimReport rep_;
  std::int64_t t0_ns_ = 0, end_ns_ = 0;
  RigidWatch rigid_;                  // what the contact loop last got
  std::vector<std::uint32_t> tools_;  // free_share's scratch
  std::int64_t rigid_checked_ns_ = 0;
  static constexpr std::int64_t kRigidCheckNs = 10'000'000;
};

}  // namespace dentsph::haptics
