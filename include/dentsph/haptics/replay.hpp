// A realtime session's recording written, read back and replayed: replaying the steps into the same
// scene reproduces the recorded tool forces (docs/haptics.md, "Recording and replay").
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "dentsph/backend.hpp"
#include "dentsph/haptics/recording.hpp"

namespace dentsph {

struct RunSummary;
struct Scene;
class State;

// The event of a switch to the instrument `name` before `step`; throws std::invalid_argument for
// a name instrument_names() does not hold.
EventSample tool_switch_event(std::uint64_t step, const std::string& name);

// Writes haptic.csv, steps.csv and events.csv into `dir` (created), numbers with 17 digits so
// that they read back exactly. Throws std::runtime_error naming the file.
void save_recording(const std::filesystem::path& dir, const Recording& r);
// Reads them back. Throws std::runtime_error naming the file, line and field.
Recording load_recording(const std::filesystem::path& dir);

// Steps `scene` from its initial state on the recorded tool poses, applying the recorded events
// before their steps, on `backend`; returns the simulated tool force after each step.
// Deterministic: the same recording gives the same forces bit for bit on the backend that
// recorded it (any thread count); another backend agrees within its parity tolerance.
// `on_event` (when set) sees the state after each event is applied; `final_state` (when given)
// receives the state at the end, and `summary` the simulation's summary (its solver's statistics
// and its cure, as an offline run's).
std::vector<Vec3> replay_steps(const Scene& scene, const Recording& r, int threads = 1, Backend backend = Backend::cpu,
                               State* final_state = nullptr,
                               const std::function<void(const State&, const EventSample&)>& on_event = {},
                               RunSummary* summary = nullptr);

// Replayed tool forces against a recording's.
struct ReplayComparison {
  std::size_t differ = 0;   // steps whose force is not the recorded one bit for bit
  std::size_t outside = 0;  // steps with a component off by more than the tolerance
  double largest = 0;       // N, the largest |difference|
  double peak = 0;          // N, the largest recorded |force|
};
// Compares `replayed` with r.steps' tool forces: a step is within the tolerance when every
// component is off by at most `rel` of the recorded peak force, or of kBackendParityForceFloor (N)
// where the peak is smaller. (Two backends differ in the order of their sums, by the last bits; over a long session
// the paste's motion amplifies that, so the bound is set by the force the session reached, not by
// each step's; a session that touched nothing reached only rounding.) Throws
// std::invalid_argument when the counts differ.
ReplayComparison compare_replay(const std::vector<Vec3>& replayed, const Recording& r, double rel);

// Energy delivered to the hand, E(t_k) = sum of F . v dt over the recorded ticks (J), with v from
// the recorded device positions (central differences). A passive rendering keeps it bounded by
// the energy the hand put in.
std::vector<double> energy_to_hand(const std::vector<HapticSample>& samples);

}  // namespace dentsph
