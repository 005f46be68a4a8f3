// Haptic devices behind one interface: what the haptic loop reads (a pose) and writes (a force),
// the limits a device can render, and the map between the device's workspace and the scene.
// read() and write() are called from the haptic loop only: they must not block, allocate, lock
// or log (the UDP device's non-blocking socket calls are its device access).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "dentsph/contact.hpp"
#include "dentsph/pose.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {

struct Scene;

// What a device can render safely, and how hard its hard contact is.
struct DeviceProfile {
  std::string name = "falcon";
  double max_force_N = 9.0;               // magnitude limit
  double max_force_rate_N_per_s = 1000;   // limit on |dF/dt| (1 N per tick at 1 kHz)
  double max_torque_N_m = 0;              // 0: the device renders no torque (3-DoF output)
  ContactParams contact;                  // the hard contact's spring, damper and friction
};
// "falcon" (Novint Falcon: 9 N), "omega" (Force Dimension omega.x: 12 N), "touch" (3D Systems
// Touch: 3.3 N), "sigma7" (Force Dimension sigma.7: 20 N and 0.4 N m of torque). Throws
// std::invalid_argument naming the known profiles otherwise.
DeviceProfile device_profile(const std::string& name);
// The profiles' names, for the command line.
const char* device_profile_names();

// The device's workspace in the scene: scene position = origin + scale * device position
// (device frame in m, axes aligned with the scene's). Forces need no map: the runtime's force
// scale turns simulated newtons into device newtons.
struct WorkspaceMap {
  Vec3 origin;      // m, scene position of the device's origin
  double scale = 1; // scene m per device m
  Vec3 to_scene(const Vec3& device) const { return origin + device * scale; }
  Vec3 to_device(const Vec3& scene) const { return (scene - origin) / scale; }
};

// The newest pose a device has.
struct DeviceSample {
  Pose pose;                   // device frame (m)
  std::int64_t stamp_ns = 0;   // runtime clock when the pose was received / measured
  double device_time_s = 0;    // the device's own clock, for velocity estimates
  std::uint32_t sequence = 0;  // increments with every new pose
  std::uint32_t buttons = 0;   // pressed buttons, a bit mask (haptic_protocol::kButtonDispense)
  // The device's session: a new number when another hand takes the device (a network client's
  // hello, or its restart): the runtime then forgets the previous session's motion, puts the
  // tool's proxy where the device is and ramps the force in from zero. 0 for a device that has
  // one session (scripted, replay).
  std::uint32_t session = 0;
  bool valid = false;          // a pose has been received at all
};

struct ForceCommand {
  Vec3 force_N;                // finite, within the profile's limits
  Vec3 torque_N_m;             // about the tool's origin; finite, within the profile's torque limit (zero
                               // for a device without torque output)
  std::uint32_t status = 0;    // haptic_protocol::ForceStatus bits
  std::uint32_t force_age_us = 0;
};

class Device {
 public:
  virtual ~Device() = default;
  virtual std::string name() const = 0;
  // Called once on the haptic thread before the first read (t0_ns: the runtime's time zero).
  virtual void start(std::int64_t t0_ns) { (void)t0_ns; }
  // The newest pose at runtime time now_ns. Returns true when the pose is new since the last call.
  virtual bool read(std::int64_t now_ns, DeviceSample& sample) = 0;
  virtual void write(std::int64_t now_ns, const ForceCommand& command) = 0;
  // A device that has played all it has (scripted, replay) asks the runtime to stop.
  virtual bool finished(std::int64_t now_ns) const { (void)now_ns; return false; }
  // Device-specific counters as a JSON object (written to summary.json under "device").
  virtual std::string report_json() const { return "{}"; }
};

// Plays the scene's tool keyframes in real time as a hand moves through them (through a 5 Hz
// critically damped low-pass, src/haptics/hand_path.hpp: no instant change of velocity at a
// keyframe, 64 ms behind them), mapped into the device frame by `map`; finished `tail_s` after the
// last keyframe (and the hand's lag), or at `duration_s` when it is positive.
std::unique_ptr<Device> make_scripted_device(const Scene& scene, const WorkspaceMap& map, double duration_s = 0,
                                             double tail_s = 0.1);

// Plays the device poses of a recorded session (haptic.csv of a recording folder) in real time.
std::unique_ptr<Device> make_replay_device(const std::filesystem::path& recording_dir);

// The network bridge: listens on UDP `port` (0: any free port) of `address`.
struct UdpDeviceOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 47000;
  double session_timeout_s = 1.0;  // a silent client's session ends (another may then connect)
  double heartbeat_interval_s = 0.1;  // heartbeats to a client while its pose is stale
  // Plausible poses (docs/haptic-protocol.md): within this distance of the device's origin (m;
  // desk devices reach about 0.1 m: a client sending millimetres is refused)...
  double workspace_radius_m = 0.3;
  // ...and no faster than a hand moves an instrument (m/s; a dentist's hand moves at centimetres a
  // second), from the pose before and from the last accepted one, with a tolerance of
  // `jump_tolerance_m` for the jitter of timestamps.
  double max_speed_m_per_s = 2;
  double jump_tolerance_m = 0.002;
  // Poses behind the newest by more than the reordering window, this many in a row and in order
  // among themselves, are a client that restarted its numbering without a hello: a new session.
  int restart_after = 3;
};
// Throws std::runtime_error naming the address when it cannot bind. `bound_port`, when given,
// receives the port it listens on.
std::unique_ptr<Device> make_udp_device(const UdpDeviceOptions& options, std::uint16_t* bound_port = nullptr);

}  // namespace dentsph
