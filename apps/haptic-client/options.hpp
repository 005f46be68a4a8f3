// The reference client's options (dentsph-haptic-client --help): the device it plays, the motion,
// and the faults it injects (docs/haptic-protocol.md, "The reference client").
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace dentsph::haptic_client {

struct Options {
  std::string host = "127.0.0.1";
  std::uint16_t port = 47000;
  double rate_hz = 1000, duration_s = 3;
  std::string motion = "press";  // press | hold | circle | still
  double depth_m = 0.03, period_s = 1.0;
  std::vector<double> axis{0, 0, -1};  // direction of press and hold (normalised)
  std::vector<double> orientation{1, 0, 0, 0};  // the instrument's, a quaternion w x y z (normalised)
  double limit_N = 9.0;
  bool torque = false;             // a 6-DoF device: ask for wrench packets (kCapabilityTorque)
  double torque_limit_N_m = 0.4;
  double drop = 0, duplicate = 0, reorder = 0, truncate = 0, garbage = 0;
  double pause_at_s = -1, pause_for_s = 0;
  std::vector<double> press_button_at_s;  // button 1 (dispense) down for press_button_for_s from each
  double press_button_for_s = 0.1;
  bool bye = true, hello = false;
  double restart_at_s = -1;        // number the poses from 1 again (same socket), as a restarted client
  double heartbeat_every_s = 0;    // heartbeats between poses
  double scale = 1;                // positions sent times this (1000: a client sending millimetres)
  double spike_at_s = -1, spike_m = 0;  // one pose at this time with x = spike_m
  double toggle_button_hz = 0;     // button 1 toggled at this rate the whole run
  double toggle_light_hz = 0;      // button 2 (the curing light) toggled at this rate the whole run
  double start_after_s = 0;        // wait this long before the first message
  double wait_s = 0;               // > 0: heartbeats until dentsph answers, at most this long, before the first pose
  unsigned seed = 1;
  std::string report;
};

// Declares every option on `app`, each with its range.
void add_options(CLI::App& app, Options& o);
// The checks CLI11 cannot make (a zero axis or orientation); normalises the orientation. Returns
// the message of a refusal, empty when the options are good.
std::string check_options(Options& o);

// The device's position at time t (m, device frame): the motion a hand would make.
std::array<double, 3> motion(const Options& o, double t);

}  // namespace dentsph::haptic_client
