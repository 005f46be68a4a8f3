// Recording of a realtime session and its deterministic replay. The haptic loop records the
// device pose and the rendered force at the haptic rate (into preallocated memory); the
// simulation loop records the tool pose it stepped with, per step, and the procedure events it
// applied. Replaying the steps into the same scene reproduces the recorded tool forces.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "dentsph/backend.hpp"
#include "dentsph/pose.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {

struct RunSummary;
struct Scene;
class State;

// One haptic tick.
struct HapticSample {
  double t = 0;                // s since the runtime started
  Vec3 device_position;        // m, device frame
  Quat device_orientation;
  Vec3 device_velocity;        // m/s, filtered estimate
  Vec3 force;                  // N, sent to the device (after limits and watchdog)
  Vec3 target;                 // N, the renderer's force before gain and limits
  Vec3 proxy_position;         // m, device frame (virtual coupling; the device's in direct mode)
  // The hard contact (contact.hpp): its proxy (m, device frame; the device's position in air) and
  // force (N, before gain and limits), and the torque sent (N m). Kept in memory, not in haptic.csv.
  Vec3 contact_proxy, contact_force, torque;
  double gain = 0;             // watchdog gain in [0, 1]
  std::uint32_t status = 0;    // haptic_protocol::ForceStatus bits
  std::uint32_t pose_sequence = 0;
};

// One simulation step.
struct StepSample {
  std::uint64_t step = 0;      // State::steps before the step
  double wall_t = 0;           // s since the runtime started
  Pose tool_pose;              // scene frame, the pose the step moved the tool to
  Vec3 tool_force;             // N, simulated (unscaled), after the step
};

struct EventSample {
  std::uint64_t step = 0;      // applied before this step
  std::uint32_t index = 0;     // into Scene::events, kButtonIncrement or kToolSwitch + k
};
// EventSample::index of an increment dispensed on request: the device's button 1 or the viewer's
// D key (dispense_increment of Recording::dispense_volume with the scene's paste, on the tooth's
// axis).
inline constexpr std::uint32_t kButtonIncrement = 0xffffffffu;
// EventSample::index of the curing light turned on or off (the device's button 2; the light over
// the cavity, Simulation::light_over_cavity): each one toggles it.
inline constexpr std::uint32_t kLightToggle = 0xfffffffeu;
// EventSample::index of a switch to instrument k of instrument_names() (the viewer's tool menu;
// switch_instrument): kToolSwitch + k.
inline constexpr std::uint32_t kToolSwitch = 0xffffff00u;
// The event of a switch to the instrument `name` before `step`; throws std::invalid_argument for
// a name instrument_names() does not hold.
EventSample tool_switch_event(std::uint64_t step, const std::string& name);

struct Recording {
  std::string mode;            // "direct" | "coupling"
  double haptic_rate_hz = 0;
  double force_scale = 1;
  std::uint64_t haptic_dropped = 0;  // ticks not recorded (capacity full)
  double dispense_volume = 0;  // m^3 of a button increment (session.json; 0: the scene's default)
  std::string backend = "cpu"; // the backend that stepped the session (session.json; older: cpu)
  std::string solver;          // the step that ran it, "paper" or "iisph" (session.json; older: none)
  std::string material;        // the paste preset it was filled with (`--material`; session.json; none: the scene's)
  double material_temperature_c = 23;  // C, that preset's temperature
  std::vector<HapticSample> haptic;
  std::vector<StepSample> steps;
  std::vector<EventSample> events;
};

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
