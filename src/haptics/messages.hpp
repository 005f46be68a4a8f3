// What the loops hand each other through triple buffers (plain data, copied whole).
#pragma once

#include <cstdint>

#include <vector>

#include "dentsph/contact.hpp"
#include "dentsph/pose.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph::haptics {

// Haptic -> simulation: the device, in the device frame.
struct ToolCommand {
  Pose pose;                  // the device's pose, its position held out of rigid surfaces (the hard
                              // contact's proxy, HardContact): where the instrument may go
  Vec3 velocity;              // m/s, filtered estimate
  // The hard contact touches a rigid surface at `pose` with this outward normal (zero in air):
  // the coupling's proxy is kept on its outer side (sim_loop.cpp).
  Vec3 contact_normal;
  std::int64_t stamp_ns = 0;  // runtime clock when the haptic loop published it
  std::uint32_t sequence = 0; // device pose sequence it came from
  std::uint64_t dispense_presses = 0;  // presses of button 1 since the start (kButtonDispense)
  std::uint64_t light_presses = 0;     // presses of button 2 since the start (kButtonLight)
  // The device session (DeviceSample::session) the pose belongs to: with the first command of a new
  // session the simulation puts the coupling's proxy at its pose, at rest, and drops the previous
  // hand's tool force (sim_loop.cpp).
  std::uint32_t session = 0;
  bool valid = false;
};

// Simulation -> haptic: the newest tool force.
struct SimOutput {
  Vec3 force_N;                    // device N: force_scale * simulated tool force
  Vec3 torque_N_m;                 // device N m: the same for the torque about the tool's origin
  Vec3 proxy_position, proxy_velocity;  // virtual coupling: the proxy (device frame)
  // Virtual coupling: no paste or wall particle was within reach of the instrument's move this step, and the proxy
  // went where the hand is (free move): the coupling renders no force.
  bool free = false;
  std::uint64_t step = 0;          // State::steps after the step
  double sim_time = 0;             // s
  std::int64_t command_stamp_ns = 0;  // stamp of the ToolCommand the step used
  std::int64_t published_ns = 0;
  bool valid = false;
};

}  // namespace dentsph::haptics

namespace dentsph::haptics {

// Simulation -> contact loop: what is rigid now (the matrix band and set paste, scene m) and the
// instrument (its particles in the tool frame, their spacing), when either changed.
struct RigidInput {
  std::vector<Vec3> particles;
  std::vector<Vec3> tool;
  real tool_spacing = 0;
};

// Contact loop -> haptic loop: the field and the instrument's shape the hard contact uses.
struct ContactWorld {
  ContactField field;
  ContactShape shape;
};

}  // namespace dentsph::haptics
