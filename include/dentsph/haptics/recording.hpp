// Recording of a realtime session: its types alone. The haptic loop records the device pose and
// the rendered force at the haptic rate (into preallocated memory); the simulation loop records
// the tool pose it stepped with, per step, and the procedure events it applied. Writing, reading
// and replaying a recording: dentsph/haptics/replay.hpp.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dentsph/pose.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {


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

}  // namespace dentsph
